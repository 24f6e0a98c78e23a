#pragma once
// Who may use the control API (docs/control-api.md "Access"), decided from a request's headers
// before its body is read. A web page the user opens must not drive the rig: the rules are those
// of the Jupyter server and Docker's API. A Host that is not an IP address, "localhost" or a name
// the user allowed is a DNS-rebinding page (403); an Origin other than the API's own, or a
// Sec-Fetch-Site other than same-origin/none, is another site's page (403); a body that is not
// application/json is a form or a no-cors fetch (415); with a token, a request without
// "Authorization: Bearer <token>" is refused (401). A chunked body is refused (411): its
// trailer fields are not bounded by the header limit.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::control {

/// The access rules of one control API listener.
struct HttpAccess {
    /// Host names a request's Host header may name besides IP addresses and "localhost"
    /// (--control-allow-host), compared without regard to case.
    std::vector<std::string> allowed_hosts;
    /// Not empty: every request carries "Authorization: Bearer <token>" (--control-token).
    std::string token;
};

/// What the access rules read of a request: its method and headers, as sent.
struct RequestHead {
    std::string_view method;
    unsigned version = 11;                 ///< 10 for HTTP/1.0, 11 for HTTP/1.1
    std::optional<std::string_view> host;  ///< absent: no Host header
    std::optional<std::string_view> origin;
    std::optional<std::string_view> sec_fetch_site;
    std::optional<std::string_view> content_type;
    std::optional<std::string_view> authorization;
    std::string_view target;   ///< the request target ("/api/rig?x=1")
    bool has_body = false;   ///< a Content-Length above 0
    bool chunked = false;    ///< Transfer-Encoding: chunked
};

/// Why a request is refused before its body is read.
struct AccessRefusal {
    unsigned status = 403;
    std::string message;
};

/// The refusal of `head` under `access`, or nothing when the request may go on.
std::optional<AccessRefusal> check_access(const HttpAccess& access, const RequestHead& head);

/// Whether `head` is a GET of one of the live view's files ("/", "/ui/app.js", "/ui/style.css"):
/// the only requests that need no token (a browser cannot send one with a page it opens; the files
/// hold no state of the rig: the page asks for the token before it reads anything). The Host and
/// Origin checks still apply.
bool is_live_view_request(const RequestHead& head);

/// The host part of a Host header value ("[::1]:8080" -> "::1", "Example:80" -> "example"),
/// lower case; nullopt when it is not of the form host[:port].
std::optional<std::string> host_name_of(std::string_view host_header);

/// Why `token` cannot be a token (empty, over 1024 characters, not printable ASCII without
/// spaces), or nothing.
std::optional<std::string> bad_token(std::string_view token);

/// The token of --control-token-file: the file's first line without surrounding white space.
/// Throws std::runtime_error naming the file and what is wrong (unreadable, empty, over 4 KiB).
std::string read_token_file(const std::string& path);

} // namespace rigsim::control
