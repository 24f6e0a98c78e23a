// The control API's live view (docs/control-api.md "The live view"): the page at "/" and its two
// files, served by the real rigsimd from what it compiled in, byte for byte the files of
// emulator/control/ui/, with a policy that keeps them to the daemon; without the token (a browser
// cannot send one with a page), while every route of the API still asks for it. What the page
// shows in a browser: tests/e2e/live_view_browser.py.
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace live_view_test {

using namespace rigsim::e2e;

/// `head` (request line and header lines, each ending "\r\n") on a new connection; its answer.
HttpAnswer fetch(const Endpoint& control, const std::string& head)
{
    TcpClient c(control);
    c.send(head + "\r\n");
    return read_answer(c);
}

std::string source_file(const std::string& relative)
{
    std::ifstream in(std::string(RIGSIM_SOURCE_DIR) + "/" + relative, std::ios::binary);
    REQUIRE(in);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_CASE("live view: the page and its files, as compiled in, with a policy that keeps them to the daemon",
          "[e2e][control][live_view]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    const struct {
        const char* path;
        const char* file;
        const char* type;
    } files[] = {{"/", "emulator/control/ui/index.html", "content-type: text/html; charset=utf-8\r\n"},
                 {"/ui/app.js", "emulator/control/ui/app.js", "content-type: text/javascript; charset=utf-8\r\n"},
                 {"/ui/style.css", "emulator/control/ui/style.css", "content-type: text/css; charset=utf-8\r\n"}};
    for (const auto& f : files) {
        INFO(f.path);
        const auto p = fetch(control, std::string("GET ") + f.path + " HTTP/1.1\r\nHost: localhost\r\n");
        CHECK(p.status == 200);
        CHECK(p.body == source_file(f.file));
        CHECK(has(p.headers, f.type));
        CHECK(has(p.headers, "content-security-policy: default-src 'none'; script-src 'self'; style-src 'self'; "
                             "connect-src 'self';"));
        CHECK(has(p.headers, "x-frame-options: deny\r\n"));
        CHECK(has(p.headers, "x-content-type-options: nosniff\r\n"));
    }
    // The page names only files the daemon serves: no other host, no inline script.
    const auto page = fetch(control, "GET /?from=bookmark HTTP/1.1\r\nHost: 127.0.0.1\r\n");
    CHECK(page.status == 200);
    CHECK_FALSE(has(page.body, "http://"));
    CHECK_FALSE(has(page.body, "https://"));
    CHECK_FALSE(has(page.body, "<script>"));
    CHECK(has(page.body, "<script src=\"/ui/app.js\" defer></script>"));

    CHECK(fetch(control, "POST / HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\nContent-Length: 2\r\n"
                         "\r\n{}")
              .status
          == 405);
    CHECK(fetch(control, "GET /ui/other.js HTTP/1.1\r\nHost: localhost\r\n").status == 404);
    // A page of another site, or reached through a name of its own, gets nothing.
    CHECK(fetch(control, "GET / HTTP/1.1\r\nHost: evil.example\r\n").status == 403);
    CHECK(fetch(control, "GET /ui/app.js HTTP/1.1\r\nHost: localhost\r\nOrigin: http://evil.example\r\n").status == 403);
}

TEST_CASE("live view: with --control-token the page comes without it, the API's routes still ask for it",
          "[e2e][control][live_view][security]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--control-token", "s3cret-token_1"}});
    const auto control = control_endpoint(daemon);
    CHECK(fetch(control, "GET / HTTP/1.1\r\nHost: localhost\r\n").status == 200);
    CHECK(fetch(control, "GET /ui/app.js HTTP/1.1\r\nHost: localhost\r\n").status == 200);
    // Only a GET of the page's own files goes without the token.
    CHECK(fetch(control, "GET /api/rig HTTP/1.1\r\nHost: localhost\r\n").status == 401);
    CHECK(fetch(control, "GET /api/events HTTP/1.1\r\nHost: localhost\r\n").status == 401);
    CHECK(fetch(control, "POST / HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\nContent-Length: 2\r\n"
                         "\r\n{}")
              .status
          == 401);
    CHECK(fetch(control, "GET /ui/../api/rig HTTP/1.1\r\nHost: localhost\r\n").status == 401);
    CHECK(fetch(control, "GET /api/rig HTTP/1.1\r\nHost: localhost\r\nAuthorization: Bearer s3cret-token_1\r\n").status
          == 200);
}

} // namespace live_view_test
