#include "emulator/control/http_access.hpp"
#include "emulator/control/live_view.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <arpa/inet.h>
#include <sys/stat.h>

namespace rigsim::control {

namespace {

std::string lower(std::string_view s)
{
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::string_view trim(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
        s.remove_suffix(1);
    return s;
}

bool is_port(std::string_view s)
{
    return !s.empty() && s.size() <= 5
           && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

bool is_ip_literal(const std::string& host)
{
    unsigned char buf[16];
    return ::inet_pton(AF_INET, host.c_str(), buf) == 1 || ::inet_pton(AF_INET6, host.c_str(), buf) == 1;
}

/// `s` quoted for a message, cut to a sane length (a header may be 8 KiB).
std::string in_quotes(std::string_view s)
{
    constexpr std::size_t kMax = 80;
    std::string out = "\"";
    for (const char c : s.substr(0, kMax))
        out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return out + (s.size() > kMax ? "\"..." : "\"");
}

/// Compares in time that depends on the lengths only, not on where the first difference is.
bool same_secret(std::string_view a, std::string_view b)
{
    if (a.size() != b.size())
        return false;
    unsigned char diff = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        diff |= static_cast<unsigned char>(a[i] ^ b[i]);
    return diff == 0;
}

bool is_json_media_type(std::string_view content_type)
{
    const auto media = lower(trim(content_type.substr(0, content_type.find(';'))));
    return media == "application/json";
}

std::optional<AccessRefusal> check_host(const HttpAccess& access, const RequestHead& head)
{
    if (!head.host) {
        if (head.version >= 11)
            return AccessRefusal{400, "an HTTP/1.1 request needs a Host header"};
        return std::nullopt;
    }
    const auto name = host_name_of(*head.host);
    if (!name)
        return AccessRefusal{400, "Host " + in_quotes(*head.host) + ": expected host[:port]"};
    if (*name == "localhost" || is_ip_literal(*name))
        return std::nullopt;
    for (const auto& allowed : access.allowed_hosts)
        if (lower(allowed) == *name)
            return std::nullopt;
    return AccessRefusal{403, "Host " + in_quotes(*head.host)
                                  + ": not an IP address, localhost or a name allowed with --control-allow-host "
                                    "(a page that reaches the daemon through another name is refused)"};
}

std::optional<AccessRefusal> check_origin(const RequestHead& head)
{
    if (head.sec_fetch_site) {
        const auto site = lower(trim(*head.sec_fetch_site));
        if (site != "same-origin" && site != "none")
            return AccessRefusal{403, "Sec-Fetch-Site " + in_quotes(site)
                                          + ": requests from other sites' pages are refused"};
    }
    if (!head.origin)
        return std::nullopt;
    const auto origin = lower(trim(*head.origin));
    if (head.host && origin == "http://" + lower(trim(*head.host)))
        return std::nullopt;
    return AccessRefusal{403, "Origin " + in_quotes(*head.origin) + ": cross-origin requests are refused"};
}

std::optional<AccessRefusal> check_token(const HttpAccess& access, const RequestHead& head)
{
    if (access.token.empty() || is_live_view_request(head))
        return std::nullopt;
    const std::string_view scheme = "bearer ";
    if (head.authorization) {
        const auto value = trim(*head.authorization);
        if (value.size() > scheme.size() && lower(value.substr(0, scheme.size())) == scheme
            && same_secret(trim(value.substr(scheme.size())), access.token))
            return std::nullopt;
    }
    return AccessRefusal{401, std::string(head.authorization ? "wrong token" : "no token")
                                  + ": this daemon takes requests with \"Authorization: Bearer <token>\" "
                                    "(--control-token)"};
}

} // namespace

std::optional<std::string> host_name_of(std::string_view host_header)
{
    auto value = trim(host_header);
    std::string_view host;
    std::string_view port;
    if (!value.empty() && value.front() == '[') {
        const auto close = value.find(']');
        if (close == std::string_view::npos)
            return std::nullopt;
        host = value.substr(1, close - 1);
        const auto rest = value.substr(close + 1);
        if (!rest.empty() && (rest.front() != ':' || !is_port(rest.substr(1))))
            return std::nullopt;
        if (host.find(':') == std::string_view::npos)
            return std::nullopt;   // brackets hold an IPv6 address only
    } else {
        const auto colon = value.find(':');
        host = value.substr(0, colon);
        if (colon != std::string_view::npos) {
            port = value.substr(colon + 1);
            if (!is_port(port))
                return std::nullopt;
        }
        const bool name_chars = std::all_of(host.begin(), host.end(), [](unsigned char c) {
            return std::isalnum(c) != 0 || c == '.' || c == '-' || c == '_';
        });
        if (!name_chars)
            return std::nullopt;
    }
    if (host.empty())
        return std::nullopt;
    auto name = lower(host);
    if (name.size() > 1 && name.back() == '.')
        name.pop_back();   // "localhost." is "localhost"
    return name;
}

bool is_live_view_request(const RequestHead& head)
{
    if (head.method != "GET")
        return false;
    return live_view_file(head.target.substr(0, head.target.find('?'))) != nullptr;
}

std::optional<AccessRefusal> check_access(const HttpAccess& access, const RequestHead& head)
{
    if (head.chunked)
        return AccessRefusal{411, "a chunked request body is refused: send the body with a Content-Length"};
    if (auto refused = check_host(access, head))
        return refused;
    if (auto refused = check_origin(head))
        return refused;
    if (auto refused = check_token(access, head))
        return refused;
    const bool bodyless_read = head.method == "GET" || head.method == "HEAD";
    if (head.content_type ? !is_json_media_type(*head.content_type) && (head.has_body || !bodyless_read)
                          : head.has_body)
        return AccessRefusal{415, "Content-Type " + (head.content_type ? in_quotes(*head.content_type) : "absent")
                                      + ": a request body must be application/json"};
    return std::nullopt;
}

std::optional<std::string> bad_token(std::string_view token)
{
    if (token.empty())
        return "empty: expected a token of printable ASCII without spaces";
    if (token.size() > 1024)
        return "longer than 1024 characters";
    if (!std::all_of(token.begin(), token.end(), [](unsigned char c) { return c > 0x20 && c < 0x7f; }))
        return "a token is printable ASCII without spaces";
    return std::nullopt;
}

std::string read_token_file(const std::string& path)
{
    constexpr std::size_t kMaxTokenFileBytes = 4096;
    const auto fail = [&](const std::string& why) {
        return std::runtime_error("--control-token-file " + path + ": " + why);
    };
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw fail(std::strerror(errno));
    if (!S_ISREG(st.st_mode))
        throw fail("not a regular file");
    if (static_cast<std::size_t>(st.st_size) > kMaxTokenFileBytes)
        throw fail("over 4 KiB: expected one line holding the token");
    std::ifstream in(path);
    std::string line;
    if (!in || !std::getline(in, line)) {
        if (in.bad() || !in.is_open())
            throw fail("cannot read it");
    }
    const auto token = trim(std::string_view(line).substr(0, line.find('\r')));
    if (auto why = bad_token(token))
        throw fail(*why);
    return std::string(token);
}

} // namespace rigsim::control
