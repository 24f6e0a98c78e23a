// Who may drive the real rigsimd's control API (docs/control-api.md "Access"): not a web page
// the user opens (foreign Host: DNS rebinding; Origin or Sec-Fetch-Site of another site; a body
// that is not application/json: a form or a no-cors fetch), not a request without the token
// when the daemon has one; and no request, however it is framed, ends the daemon.
#include "control_support.hpp"
#include "e2e_support.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace control_access_test {

using namespace rigsim::e2e;

/// `head` (request line and header lines, each ending "\r\n") and `body` sent on a new
/// connection to `control`; its answer.
HttpAnswer raw(const Endpoint& control, const std::string& head, const std::string& body = {})
{
    TcpClient c(control);
    c.send(head + "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body);
    return read_answer(c);
}

bool has(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

const std::string kUnplug = R"({"device": "mcs0", "kind": "unplugged"})";

TEST_CASE("control access: a chunked body is refused with 411 before its trailer is read, the daemon serves on",
          "[e2e][control][security]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    TcpClient mcs(daemon.endpoint("mcs0"));
    REQUIRE(mcs.request(":GP0\n") == ":P0,0\n");

    // The headers alone are answered: nothing of the body or its trailer is read.
    TcpClient chunked(control);
    chunked.send("POST /api/clock HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n"
                 "Transfer-Encoding: chunked\r\n\r\n");
    const auto refused = read_answer(chunked);
    CHECK(refused.status == 411);
    CHECK(has(refused.body, "chunked"));
    CHECK(chunked.wait_for_eof(kAnswerTimeout));

    // What ended the daemon before: a trailer field of 64 KiB and more, sent in one go.
    {
        TcpClient attack(control);
        const std::string big(70 * 1024, 'a');
        try {
            attack.send("POST /api/clock HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n"
                        "Transfer-Encoding: chunked\r\n\r\n2\r\n{}\r\n0\r\nX-Big: " + big + "\r\n\r\n");
        } catch (const std::exception&) {
            // The daemon may close before the whole request is written: that is the point.
        }
        CHECK(attack.wait_for_eof(kAnswerTimeout));
    }
    CHECK(daemon.running());
    CHECK(mcs.request(":GP0\n") == ":P0,0\n");
    TcpClient api(control);
    CHECK(http(api, "GET", "/api/clock").status == 200);
}

TEST_CASE("control access: a Host that is not an address, localhost or an allowed name gets 403",
          "[e2e][control][security]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0", "--control-allow-host", "rig.lab"}});
    const auto control = control_endpoint(daemon);
    const std::string port = std::to_string(control.port);

    for (const std::string& host : std::vector<std::string>{"evil.example", "evil.example:" + port, "127.0.0.1.evil.example", "rig.lab.evil"}) {
        INFO("Host: " << host);
        const auto a = raw(control, "GET /api/rig HTTP/1.1\r\nHost: " + host + "\r\n");
        CHECK(a.status == 403);
        CHECK(has(a.body, "--control-allow-host"));
        CHECK_FALSE(has(a.body, "mcs0"));   // nothing of the rig is read
    }
    CHECK(raw(control, "GET /api/rig HTTP/1.1\r\n").status == 400);   // HTTP/1.1 needs a Host
    for (const std::string& host : std::vector<std::string>{"127.0.0.1:" + port, "localhost:" + port, "LOCALHOST", "[::1]:" + port,
                                   "rig.lab", "Rig.Lab:" + port}) {
        INFO("Host: " << host);
        const auto a = raw(control, "GET /api/rig HTTP/1.1\r\nHost: " + host + "\r\n");
        CHECK(a.status == 200);
        CHECK(has(a.body, "mcs0"));
    }
    CHECK(has(daemon.log(), "refused GET /api/rig"));
}

TEST_CASE("control access: another site's page (Origin, Sec-Fetch-Site) gets 403 and changes nothing",
          "[e2e][control][security]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    const std::string host = "127.0.0.1:" + std::to_string(control.port);
    const std::string post = "POST /api/faults HTTP/1.1\r\nHost: " + host + "\r\nContent-Type: application/json\r\n";

    CHECK(raw(control, post + "Origin: http://evil.example\r\n", kUnplug).status == 403);
    CHECK(raw(control, post + "Origin: null\r\n", kUnplug).status == 403);
    CHECK(raw(control, post + "Origin: http://localhost:" + std::to_string(control.port) + "\r\n", kUnplug).status
          == 403);   // another origin than the one the request names
    CHECK(raw(control, post + "Sec-Fetch-Site: cross-site\r\n", kUnplug).status == 403);
    CHECK(raw(control, post + "Sec-Fetch-Site: same-site\r\n", kUnplug).status == 403);
    CHECK(raw(control, "GET /api/faults HTTP/1.1\r\nHost: " + host + "\r\n").body.find("unplugged")
          == std::string::npos);

    // The API's own origin (a page the daemon served, were there one) and a tool are served.
    const auto own = raw(control, post + "Origin: http://" + host + "\r\nSec-Fetch-Site: same-origin\r\n", kUnplug);
    CHECK(own.status == 201);
}

TEST_CASE("control access: a body that is not application/json gets 415 and injects nothing",
          "[e2e][control][security]")
{
    Daemon daemon(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    const auto control = control_endpoint(daemon);
    const std::string post = "POST /api/faults HTTP/1.1\r\nHost: localhost\r\n";
    TcpClient mcs(daemon.endpoint("mcs0"));

    // What fetch(url, {method: "POST", mode: "no-cors", body}) and an HTML form send.
    for (const std::string type : {"text/plain;charset=UTF-8", "application/x-www-form-urlencoded",
                                   "multipart/form-data; boundary=x", "application/jsonx"}) {
        INFO("Content-Type: " << type);
        const auto a = raw(control, post + "Content-Type: " + type + "\r\n", kUnplug);
        CHECK(a.status == 415);
        CHECK(has(a.body, "application/json"));
    }
    CHECK(raw(control, post, kUnplug).status == 415);   // a body without a Content-Type
    // A bodiless POST with a form type is refused too (a form can send one).
    CHECK(raw(control, "POST /api/reset HTTP/1.1\r\nHost: localhost\r\nContent-Type: text/plain\r\n").status == 415);
    const auto faults = raw(control, "GET /api/faults HTTP/1.1\r\nHost: localhost\r\n");
    CHECK(faults.status == 200);
    CHECK_FALSE(has(faults.body, "unplugged"));
    CHECK(mcs.request(":GP0\n") == ":P0,0\n");   // not unplugged

    const auto json = raw(control, post + "Content-Type: Application/JSON; charset=utf-8\r\n", kUnplug);
    CHECK(json.status == 201);
    const auto headers_ok = raw(control, "GET /api/clock HTTP/1.1\r\nHost: localhost\r\n");
    CHECK(headers_ok.status == 200);
}

TEST_CASE("control access: with --control-token a request without the bearer token gets 401",
          "[e2e][control][security]")
{
    TempDir dir;
    write_file(dir.file("token"), "  s3cret-token_1\n");
    for (const auto& flags :
         {std::vector<std::string>{"--control-token", "s3cret-token_1"},
          std::vector<std::string>{"--control-token-file", dir.file("token")}}) {
        INFO(flags[0]);
        std::vector<std::string> args{"--control", "127.0.0.1:0"};
        args.insert(args.end(), flags.begin(), flags.end());
        Daemon daemon(Daemon::Options{{}, {}, args});
        const auto control = control_endpoint(daemon);
        const std::string get = "GET /api/rig HTTP/1.1\r\nHost: localhost\r\n";

        const auto none = raw(control, get);
        CHECK(none.status == 401);
        CHECK(has(none.body, "no token"));
        CHECK(raw(control, get + "Authorization: Bearer s3cret-token_2\r\n").status == 401);
        CHECK(raw(control, get + "Authorization: Basic czNjcmV0LXRva2VuXzE=\r\n").status == 401);
        CHECK(raw(control, "POST /api/faults HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n",
                  kUnplug)
                  .status
              == 401);
        const auto ok = raw(control, get + "Authorization: Bearer s3cret-token_1\r\n");
        CHECK(ok.status == 200);
        CHECK(has(ok.body, "mcs0"));
        CHECK(raw(control, get + "authorization: bearer s3cret-token_1\r\n").status == 200);
        CHECK_FALSE(has(daemon.log(), "s3cret"));   // the log never shows the token
    }
}

TEST_CASE("control access: bad token flags exit 2 naming the flag, beyond loopback the daemon warns",
          "[e2e][control][security][cli]")
{
    TempDir dir;
    write_file(dir.file("empty"), "\n");
    const std::vector<std::vector<std::string>> bad = {
        {"--control-token", ""},
        {"--control-token", "two words"},
        {"--control-token-file", dir.file("absent")},
        {"--control-token-file", dir.file("empty")},
        {"--control-token-file", dir.path()},
        {"--control-token", "a", "--control-token", "b"},
        {"--control-allow-host", "rig.lab:80"},
        {"--control-allow-host", "a/b"},
    };
    for (const auto& args : bad) {
        const auto r = run_rigsimd(args);
        INFO(args[0] << " " << args[1] << ": " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(has(r.err, args[0].substr(0, 15)));
    }

    Daemon open(Daemon::Options{{}, {}, {"--control", "0.0.0.0:0"}});
    CHECK(has(open.log(), "beyond loopback"));
    CHECK(has(open.log(), "no --control-token"));
    Daemon local(Daemon::Options{{}, {}, {"--control", "127.0.0.1:0"}});
    CHECK_FALSE(has(local.log(), "beyond loopback"));
}

} // namespace control_access_test
