#pragma once
// The live view (docs/control-api.md#the-live-view): a page the control API serves at "/", with
// its script and style sheet, compiled into the daemon from emulator/control/ui/ (no file is read
// at run time, nothing is fetched from elsewhere). The page reads the rig through the API's own
// routes and follows its event stream.

#include <string_view>

namespace rigsim::control {

/// One file of the live view.
struct LiveViewFile {
    std::string_view path;           ///< "/", "/ui/app.js", "/ui/style.css"
    std::string_view content_type;   ///< "text/html; charset=utf-8", ...
    std::string_view body;
};

/// The live view's file at `path` (a request path without its query), or nullptr.
const LiveViewFile* live_view_file(std::string_view path);

/// The Content-Security-Policy the files are served with: scripts, styles and requests from the
/// daemon only, no frames, no plug-ins, no inline script.
inline constexpr std::string_view kLiveViewPolicy =
    "default-src 'none'; script-src 'self'; style-src 'self'; connect-src 'self'; img-src 'self'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

} // namespace rigsim::control
