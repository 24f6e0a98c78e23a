// rigsim-tap: sits between a client and a unit, passes every byte both ways unchanged and at once,
// and records what crossed (docs/conformance.md). Built from rigsim's framers and codecs.

#include "emulator/tap/recording.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

constexpr std::string_view kUsage = R"(Usage: rigsim-tap --protocol apt|mcs|mcs2 --listen pty:PATH|tcp:ADDR:PORT
                  --to serial:DEVICE[,BAUD]|tcp:HOST:PORT --record FILE
Sit between a client and a real unit: every byte passes both ways unchanged, as it is read, and
FILE gets each frame or line with its direction, its time, its raw bytes and what rigsim's codec
reads in it (docs/conformance.md, "The recording format"), flushed line by line.

  --protocol NAME   how to cut the bytes into frames for the record: apt, mcs or mcs2
  --listen WHERE    where the client connects: pty:PATH (a pseudo-terminal, PATH a symlink to it)
                    or tcp:ADDR:PORT (one client at a time; port 0: any free one, printed)
  --to WHERE        the unit: serial:DEVICE[,BAUD] (raw, 8N1; default 115200) or tcp:HOST:PORT
  --record FILE     the recording (JSON lines; created or truncated)
  --help            this text

A client may go and come back; the unit may be unplugged (its serial port is opened again when a
client next sends). SIGINT and SIGTERM end the tap. Exit status: 0 after a signal, 2 on bad
arguments or when FILE cannot be written.
)";

[[noreturn]] void usage_error(const std::string& what)
{
    std::cerr << "rigsim-tap: " << what << " (see --help)\n";
    std::exit(2);
}

struct Options {
    rigsim::tap::Protocol protocol = rigsim::tap::Protocol::Apt;
    std::string listen;
    std::string to;
    std::string record;
};

Options parse(int argc, char** argv)
{
    Options o;
    bool protocol = false;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (a == "--help") {
            std::cout << kUsage;
            std::exit(0);
        }
        if (i + 1 >= argc)
            usage_error("unknown option or missing value: " + std::string(a));
        const std::string v = argv[++i];
        if (a == "--protocol") {
            if (!rigsim::tap::parse_protocol(v, o.protocol))
                usage_error("--protocol: expected apt, mcs or mcs2, got \"" + v + "\"");
            protocol = true;
        } else if (a == "--listen") {
            if (v.rfind("pty:", 0) != 0 && v.rfind("tcp:", 0) != 0)
                usage_error("--listen: expected pty:PATH or tcp:ADDR:PORT, got \"" + v + "\"");
            o.listen = v;
        } else if (a == "--to") {
            if (v.rfind("serial:", 0) != 0 && v.rfind("tcp:", 0) != 0)
                usage_error("--to: expected serial:DEVICE[,BAUD] or tcp:HOST:PORT, got \"" + v + "\"");
            o.to = v;
        } else if (a == "--record") {
            o.record = v;
        } else {
            usage_error("unknown option: " + std::string(a));
        }
    }
    if (!protocol)
        usage_error("--protocol is required");
    if (o.listen.empty())
        usage_error("--listen is required");
    if (o.to.empty())
        usage_error("--to is required");
    if (o.record.empty())
        usage_error("--record is required");
    return o;
}

/// "ADDR:PORT" -> its parts; usage_error naming `flag` otherwise.
std::pair<std::string, std::uint16_t> host_port(const std::string& s, const char* flag)
{
    const auto colon = s.rfind(':');
    if (colon == std::string::npos || colon == 0)
        usage_error(std::string(flag) + ": expected HOST:PORT, got \"" + s + "\"");
    char* end = nullptr;
    const long port = std::strtol(s.c_str() + colon + 1, &end, 10);
    if (*end != '\0' || port < 0 || port > 65535 || end == s.c_str() + colon + 1)
        usage_error(std::string(flag) + ": expected a port 0..65535, got \"" + s.substr(colon + 1) + "\"");
    return {s.substr(0, colon), static_cast<std::uint16_t>(port)};
}

speed_t speed_of(long baud)
{
    switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return 0;
    }
}

/// A file descriptor in raw mode (8N1, no echo, no line discipline) at `speed` (0: unchanged).
void make_raw(int fd, speed_t speed)
{
    termios t{};
    if (tcgetattr(fd, &t) != 0)
        return;   // not a terminal (a test's FIFO): nothing to set
    cfmakeraw(&t);
    t.c_cflag |= CLOCAL | CREAD;
    if (speed != 0) {
        cfsetispeed(&t, speed);
        cfsetospeed(&t, speed);
    }
    tcsetattr(fd, TCSANOW, &t);
}

class Tap {
public:
    Tap(asio::io_context& io, const Options& o, rigsim::tap::Recorder& rec)
        : io_(io), o_(o), rec_(rec), start_(std::chrono::steady_clock::now()), retry_(io)
    {
    }

    void start()
    {
        if (o_.listen.rfind("tcp:", 0) == 0) {
            const auto [host, port] = host_port(o_.listen.substr(4), "--listen");
            acceptor_.emplace(io_, tcp::endpoint(asio::ip::make_address(host), port));
            std::cout << "rigsim-tap: listening on tcp " << host << ":" << acceptor_->local_endpoint().port()
                      << std::endl;
            accept();
        } else {
            open_pty(o_.listen.substr(4));
        }
    }

    void stop()
    {
        rec_.event("stop", conn_, now_us(), nlohmann::json::object());
        if (acceptor_)
            acceptor_->close();
        close_client();
        close_unit();
        retry_.cancel();
    }

private:
    std::int64_t now_us() const
    {
        return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start_).count();
    }

    void accept()
    {
        acceptor_->async_accept([this](boost::system::error_code ec, tcp::socket s) {
            if (ec == asio::error::operation_aborted)
                return;
            if (!ec) {
                if (client_) {   // one client at a time: the unit has one line
                    s.close();
                } else {
                    const auto peer = s.remote_endpoint(ec);
                    const int fd = ::dup(s.native_handle());
                    s.close();
                    client_.emplace(io_, fd);
                    begin_client("tcp " + peer.address().to_string() + ":" + std::to_string(peer.port()));
                }
            }
            accept();
        });
    }

    void open_pty(const std::string& path)
    {
        const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
        if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0)
            usage_error("--listen: cannot open a pseudo-terminal");
        const char* slave = ::ptsname(master);
        // Keep the slave open: the client's opening and closing it then never hangs the master up.
        pty_slave_ = ::open(slave, O_RDWR | O_NOCTTY);
        make_raw(pty_slave_, 0);
        pty_speed_ = client_speed();
        ::unlink(path.c_str());
        if (::symlink(slave, path.c_str()) != 0)
            usage_error("--listen: cannot make the symlink " + path);
        pty_link_ = path;
        std::cout << "rigsim-tap: listening on pty " << path << " -> " << slave << std::endl;
        client_.emplace(io_, master);
        begin_client("pty");
    }

    void begin_client(const std::string& peer)
    {
        ++conn_;
        rec_.event("connect", conn_, now_us(), {{"peer", peer}});
        if (!unit_)
            open_unit();
        read_client();
        if (unit_ && !unit_reading_)
            read_unit();
    }

    bool open_unit()
    {
        if (o_.to.rfind("tcp:", 0) == 0) {
            const auto [host, port] = host_port(o_.to.substr(4), "--to");
            tcp::socket s(io_);
            boost::system::error_code ec;
            s.connect(tcp::endpoint(asio::ip::make_address(host, ec), port), ec);
            if (ec) {
                rec_.event("unit_lost", conn_, now_us(), {{"error", ec.message()}});
                return false;
            }
            unit_.emplace(io_, ::dup(s.native_handle()));
            s.close();
        } else {
            std::string dev = o_.to.substr(7);
            long baud = 115200;
            if (const auto comma = dev.find(','); comma != std::string::npos) {
                baud = std::strtol(dev.c_str() + comma + 1, nullptr, 10);
                dev.resize(comma);
            }
            const int fd = ::open(dev.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
            if (fd < 0) {
                rec_.event("unit_lost", conn_, now_us(), {{"error", "cannot open " + dev}});
                return false;
            }
            make_raw(fd, speed_of(baud));
            unit_.emplace(io_, fd);
        }
        rec_.event("unit", conn_, now_us(), {{"to", o_.to}});
        return true;
    }

    void read_client()
    {
        client_->async_read_some(asio::buffer(from_client_), [this](boost::system::error_code ec, std::size_t n) {
            if (ec) {
                if (ec != asio::error::operation_aborted)
                    client_gone(ec.message());
                return;
            }
            const std::string_view data(from_client_.data(), n);
            const bool unit = unit_ || open_unit();
            forward_baud();   // the rate the client set before it wrote these bytes
            rec_.bytes(conn_, rigsim::tap::Direction::In, data, now_us());
            if (!unit) {   // unplugged: these bytes had nowhere to go
                read_client();
                return;
            }
            if (!unit_reading_)
                read_unit();
            asio::async_write(*unit_, asio::buffer(data), [this](boost::system::error_code wec, std::size_t) {
                if (wec) {
                    unit_gone(wec.message());
                    return;
                }
                if (client_)
                    read_client();   // the next read only once these bytes are out: bounded memory
            });
        });
    }

    void read_unit()
    {
        unit_reading_ = true;
        unit_->async_read_some(asio::buffer(from_unit_), [this](boost::system::error_code ec, std::size_t n) {
            unit_reading_ = false;
            if (ec) {
                if (ec != asio::error::operation_aborted)
                    unit_gone(ec == asio::error::eof ? "the unit closed the connection" : ec.message());
                return;
            }
            const std::string_view data(from_unit_.data(), n);
            rec_.bytes(conn_, rigsim::tap::Direction::Out, data, now_us());
            if (!client_) {
                read_unit();
                return;
            }
            asio::async_write(*client_, asio::buffer(data), [this](boost::system::error_code wec, std::size_t) {
                if (wec) {
                    client_gone(wec.message());
                    return;
                }
                if (unit_)
                    read_unit();
            });
        });
    }

    /// The output speed the client set on the tap's pty (0: not a pty).
    speed_t client_speed() const
    {
        termios t{};
        if (pty_slave_ < 0 || ::tcgetattr(pty_slave_, &t) != 0)
            return 0;
        return ::cfgetospeed(&t);
    }

    /// A baud rate the client set on the pty since the last bytes goes to a serial unit before
    /// them, as it would on the unit's own port (a client at the wrong rate gets what the unit gives).
    void forward_baud()
    {
        const speed_t speed = client_speed();
        if (speed == pty_speed_ || o_.to.rfind("serial:", 0) != 0 || !unit_)
            return;
        pty_speed_ = speed;
        make_raw(unit_->native_handle(), speed);
        static constexpr std::pair<speed_t, long> kRates[] = {
            {B1200, 1200},     {B2400, 2400},     {B4800, 4800},     {B9600, 9600},     {B19200, 19200},
            {B38400, 38400},   {B57600, 57600},   {B115200, 115200}, {B230400, 230400}, {B460800, 460800},
            {B921600, 921600}};
        long baud = 0;
        for (const auto& [s, b] : kRates)
            if (s == speed)
                baud = b;
        rec_.event("baud", conn_, now_us(), {{"baud", baud}});
    }

    void client_gone(const std::string& why)
    {
        rec_.event("disconnect", conn_, now_us(), {{"reason", why}});
        close_client();
        if (o_.to.rfind("tcp:", 0) == 0)
            close_unit();   // a TCP unit: each client has a connection of its own
    }

    void unit_gone(const std::string& why)
    {
        rec_.event("unit_lost", conn_, now_us(), {{"error", why}});
        close_unit();
        if (o_.to.rfind("tcp:", 0) == 0 && acceptor_)
            close_client();   // the unit ended the session: so does the tap, for its client
    }

    void close_client()
    {
        if (!client_)
            return;
        boost::system::error_code ec;
        if (acceptor_) {
            client_->close(ec);
            client_.reset();
        }
    }

    void close_unit()
    {
        if (!unit_)
            return;
        boost::system::error_code ec;
        unit_->close(ec);
        unit_.reset();
        unit_reading_ = false;
    }

    asio::io_context& io_;
    const Options& o_;
    rigsim::tap::Recorder& rec_;
    std::chrono::steady_clock::time_point start_;
    asio::steady_timer retry_;
    std::optional<tcp::acceptor> acceptor_;
    std::optional<asio::posix::stream_descriptor> client_;
    std::optional<asio::posix::stream_descriptor> unit_;
    bool unit_reading_ = false;
    int pty_slave_ = -1;
    speed_t pty_speed_ = 0;   ///< the pty's speed last forwarded (at first: what it was opened with)
    std::string pty_link_;
    std::uint64_t conn_ = 0;
    std::array<char, 4096> from_client_{};
    std::array<char, 4096> from_unit_{};

public:
    ~Tap()
    {
        if (pty_slave_ >= 0)
            ::close(pty_slave_);
        if (!pty_link_.empty())
            ::unlink(pty_link_.c_str());
    }
};

} // namespace

int main(int argc, char** argv)
{
    const auto o = parse(argc, argv);
    try {
        nlohmann::json header = {{"listen", o.listen}, {"to", o.to}, {"program", "rigsim-tap"}};
        rigsim::tap::Recorder rec(o.record, o.protocol, header);
        asio::io_context io;
        Tap tap(io, o, rec);
        tap.start();
        asio::signal_set signals(io, SIGINT, SIGTERM);
        signals.async_wait([&](boost::system::error_code, int) {
            tap.stop();
            io.stop();
        });
        io.run();
    } catch (const std::exception& e) {
        std::cerr << "rigsim-tap: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
