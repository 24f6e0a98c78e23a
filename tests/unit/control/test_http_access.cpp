// The control API's access rules (emulator/control/http_access.hpp) on request heads.
#include "emulator/control/http_access.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace test_http_access {

using rigsim::control::check_access;
using rigsim::control::HttpAccess;
using rigsim::control::RequestHead;

RequestHead get(std::string_view host)
{
    RequestHead head;
    head.method = "GET";
    head.host = host;
    return head;
}

RequestHead post_json(std::string_view host)
{
    RequestHead head = get(host);
    head.method = "POST";
    head.content_type = "application/json";
    head.has_body = true;
    return head;
}

unsigned status_of(const HttpAccess& access, const RequestHead& head)
{
    const auto refused = check_access(access, head);
    return refused ? refused->status : 0;
}

TEST_CASE("http access: Host names an address, localhost or an allowed name", "[unit][control][security]")
{
    const HttpAccess none;
    for (const char* host : {"127.0.0.1", "127.0.0.1:8080", "[::1]:1", "[::1]", "localhost", "LocalHost:80",
                             "localhost.", "10.1.2.3:65535"}) {
        INFO(host);
        CHECK(status_of(none, get(host)) == 0);
    }
    for (const char* host : {"evil.example", "evil.example:80", "localhost.evil", "127.0.0.1.nip.io"}) {
        INFO(host);
        CHECK(status_of(none, get(host)) == 403);
    }
    for (const char* host : {"", ":80", "a b", "[::1", "[127.0.0.1]", "host:port", "host:123456", "h/x"}) {
        INFO(host);
        CHECK(status_of(none, get(host)) == 400);
    }
    HttpAccess allowed;
    allowed.allowed_hosts = {"Rig.Lab"};
    CHECK(status_of(allowed, get("rig.lab:9000")) == 0);
    CHECK(status_of(allowed, get("RIG.LAB")) == 0);
    CHECK(status_of(allowed, get("other.lab")) == 403);

    RequestHead no_host;
    no_host.method = "GET";
    CHECK(status_of(none, no_host) == 400);
    no_host.version = 10;   // HTTP/1.0 has no Host: a local tool
    CHECK(status_of(none, no_host) == 0);
}

TEST_CASE("http access: another origin, another site, a chunked body are refused", "[unit][control][security]")
{
    const HttpAccess none;
    auto head = post_json("127.0.0.1:5000");
    head.origin = "http://127.0.0.1:5000";
    CHECK(status_of(none, head) == 0);
    head.origin = "HTTP://127.0.0.1:5000";
    CHECK(status_of(none, head) == 0);
    for (const char* origin : {"http://evil.example", "null", "https://127.0.0.1:5000", "http://127.0.0.1:5001",
                               "http://localhost:5000"}) {
        INFO(origin);
        head.origin = origin;
        CHECK(status_of(none, head) == 403);
    }
    head.origin.reset();
    for (const char* site : {"cross-site", "same-site"}) {
        head.sec_fetch_site = site;
        CHECK(status_of(none, head) == 403);
    }
    for (const char* site : {"same-origin", "none", "Same-Origin"}) {
        head.sec_fetch_site = site;
        CHECK(status_of(none, head) == 0);
    }
    head.sec_fetch_site.reset();
    head.chunked = true;
    CHECK(status_of(none, head) == 411);
}

TEST_CASE("http access: a body is application/json, with a Content-Type", "[unit][control][security]")
{
    const HttpAccess none;
    auto head = post_json("localhost");
    for (const char* type : {"application/json", "application/json; charset=utf-8", " Application/JSON ;x=y"}) {
        head.content_type = type;
        CHECK(status_of(none, head) == 0);
    }
    for (const char* type : {"text/plain", "text/plain;charset=UTF-8", "application/x-www-form-urlencoded",
                             "multipart/form-data; boundary=b", "application/json-seq", ""}) {
        INFO(type);
        head.content_type = type;
        CHECK(status_of(none, head) == 415);
    }
    head.content_type.reset();
    CHECK(status_of(none, head) == 415);   // a body without a type
    head.has_body = false;
    CHECK(status_of(none, head) == 0);     // a bodiless POST without a type (curl -X POST)
    head.content_type = "text/plain";
    CHECK(status_of(none, head) == 415);   // a form can send a bodiless text/plain POST
    auto read = get("localhost");
    read.content_type = "text/html";
    CHECK(status_of(none, read) == 0);     // a bodiless GET's Content-Type means nothing
}

TEST_CASE("http access: a token is a bearer token compared whole", "[unit][control][security]")
{
    HttpAccess access;
    access.token = "abc123";
    auto head = get("localhost");
    CHECK(status_of(access, head) == 401);
    CHECK(check_access(access, head)->message.find("no token") == 0);
    for (const char* value : {"Bearer abc12", "Bearer abc1234", "Bearer ", "abc123", "Basic abc123", "Bearerabc123"}) {
        INFO(value);
        head.authorization = value;
        CHECK(status_of(access, head) == 401);
    }
    for (const char* value : {"Bearer abc123", "bearer abc123", "BEARER  abc123 "}) {
        INFO(value);
        head.authorization = value;
        CHECK(status_of(access, head) == 0);
    }
    // The Host rule comes first: a rebinding page learns nothing about the token.
    head.host = "evil.example";
    CHECK(status_of(access, head) == 403);
}

TEST_CASE("http access: the live view's files alone need no token, and only by GET", "[unit][control][security]")
{
    HttpAccess access;
    access.token = "abc123";
    for (const char* target : {"/", "/?x=1", "/ui/app.js", "/ui/style.css"}) {
        INFO(target);
        auto head = get("localhost");
        head.target = target;
        CHECK(status_of(access, head) == 0);
        head.method = "HEAD";
        CHECK(status_of(access, head) == 401);
        head.method = "GET";
        head.host = "evil.example";   // the Host and Origin rules still hold
        CHECK(status_of(access, head) == 403);
    }
    for (const char* target : {"/api/rig", "/ui/", "/ui/../api/rig", "/index.html", "//", "/api/events"}) {
        INFO(target);
        auto head = get("localhost");
        head.target = target;
        CHECK(status_of(access, head) == 401);
    }
    auto post = post_json("localhost");
    post.target = "/";
    CHECK(status_of(access, post) == 401);
}

TEST_CASE("http access: tokens and token files", "[unit][control][security]")
{
    using rigsim::control::bad_token;
    using rigsim::control::read_token_file;
    CHECK_FALSE(bad_token("tok-EN_1.~"));
    CHECK(bad_token(""));
    CHECK(bad_token("a b"));
    CHECK(bad_token("tab\there"));
    CHECK(bad_token(std::string(1025, 'x')));
    CHECK_FALSE(bad_token(std::string(1024, 'x')));

    char name[] = "/tmp/rigsim-token-XXXXXX";
    const int fd = ::mkstemp(name);
    REQUIRE(fd >= 0);
    ::close(fd);
    const std::string path = name;
    const auto write = [&](const std::string& text) { std::ofstream(path, std::ios::trunc) << text; };
    write("  secret\r\nsecond line\n");
    CHECK(read_token_file(path) == "secret");
    write("\n");
    CHECK_THROWS_WITH(read_token_file(path), Catch::Contains(path) && Catch::Contains("empty"));
    write(std::string(5000, 'x'));
    CHECK_THROWS_WITH(read_token_file(path), Catch::Contains("4 KiB"));
    std::remove(name);
    CHECK_THROWS_WITH(read_token_file(path), Catch::Contains("No such file"));
    CHECK_THROWS_WITH(read_token_file("/tmp"), Catch::Contains("not a regular file"));
}

} // namespace test_http_access
