// librigsim_modemlines.so: an LD_PRELOAD shim giving a Linux pty slave the modem lines it
// lacks, so that serial clients which toggle RTS/DTR (pyserial `port.rts = True`, the APT
// set-up sequence) work unmodified on rigsimd's pty:
//
//     LD_PRELOAD=/usr/local/lib/librigsim_modemlines.so python3 my_apt_client.py
//
// Why: the pty driver implements no tiocmget/tiocmset, so TIOCMGET, TIOCMSET, TIOCMBIS and
// TIOCMBIC fail with ENOTTY on the slave whatever the daemon does, and the kernel's pty
// cannot be changed from user space (no CUSE either). The shim wraps ioctl(): when the real
// call fails with ENOTTY on a Unix98 pty slave, it emulates the lines for that fd:
//  * RTS and DTR as the client last set them, asserted initially (as after open on a real
//    port);
//  * CTS, DSR and CD always asserted (the emulated controller is always ready, so a client
//    with RTS/CTS flow control may write), RI never;
//  * TIOCGICOUNT: all interrupt counters zero (the input lines never change).
// TIOCMIWAIT is not emulated (the lines never change, so it could only block forever): it
// still fails with ENOTTY. Every other request, every other kind of fd, and every call the
// kernel itself answers pass straight through, so the shim is inert once a kernel gives
// ptys modem lines.
//
// The per-fd state lives in a fixed table of atomic words (lock-free, so close() stays
// async-signal-safe); fds beyond the table pass through. close() is wrapped too, so a port
// reopened on the same fd number starts with RTS and DTR asserted again. Dependencies: libc
// (and libdl on glibc < 2.34) only; no C++ runtime is used.

#include <dlfcn.h>
#include <linux/serial.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdarg>
#include <cstdint>
#include <cstring>

namespace {

using IoctlFn = int (*)(int, unsigned long, ...);
using CloseFn = int (*)(int);

/// Unix98 pty slaves (/dev/pts/N): majors 136..143 (Documentation/admin-guide/devices.txt).
constexpr unsigned kPtySlaveMajorFirst = 136;
constexpr unsigned kPtySlaveMajorLast = 143;

/// fds 0..kSlots-1 get emulated lines; higher fds pass through.
constexpr int kSlots = 4096;

/// A slot word: bit 0 says the slot is in use, the TIOCM_RTS and TIOCM_DTR bits are the
/// client's lines, the high 32 bits the device (major << 20 | minor) the state belongs to.
constexpr std::uint64_t kInUse = 1;
constexpr std::uint64_t kOutputLines = TIOCM_RTS | TIOCM_DTR;
/// Lines driven by the emulated controller: always ready.
constexpr int kInputLines = TIOCM_CTS | TIOCM_DSR | TIOCM_CD;

static_assert((kOutputLines & kInUse) == 0, "slot flag overlaps a modem line bit");
static_assert(std::atomic<std::uint64_t>::is_always_lock_free, "slots must be lock-free");

std::atomic<std::uint64_t> slots[kSlots];
std::atomic<IoctlFn> real_ioctl_fn{nullptr};
std::atomic<CloseFn> real_close_fn{nullptr};

IoctlFn real_ioctl()
{
    IoctlFn fn = real_ioctl_fn.load(std::memory_order_acquire);
    if (!fn) {
        fn = reinterpret_cast<IoctlFn>(::dlsym(RTLD_NEXT, "ioctl"));
        real_ioctl_fn.store(fn, std::memory_order_release);
    }
    return fn;
}

CloseFn real_close()
{
    CloseFn fn = real_close_fn.load(std::memory_order_acquire);
    if (!fn) {
        fn = reinterpret_cast<CloseFn>(::dlsym(RTLD_NEXT, "close"));
        real_close_fn.store(fn, std::memory_order_release);
    }
    return fn;
}

bool is_modem_request(unsigned long request)
{
    return request == TIOCMGET || request == TIOCMSET || request == TIOCMBIS ||
           request == TIOCMBIC || request == TIOCGICOUNT;
}

/// The device key of `fd` if it is a Unix98 pty slave, else 0 (never a valid key: the
/// major is at least 136).
std::uint32_t pty_slave_key(int fd)
{
    struct stat st;
    if (::fstat(fd, &st) != 0 || !S_ISCHR(st.st_mode))
        return 0;
    const unsigned maj = major(st.st_rdev);
    if (maj < kPtySlaveMajorFirst || maj > kPtySlaveMajorLast)
        return 0;
    return static_cast<std::uint32_t>(maj << 20 | (minor(st.st_rdev) & 0xfffff));
}

/// The emulated ioctl on a pty slave `fd` with device key `key`; returns 0 or -1 + errno.
int emulate(int fd, std::uint32_t key, unsigned long request, void* arg)
{
    if (!arg) {
        errno = EFAULT;
        return -1;
    }
    if (request == TIOCGICOUNT) {
        std::memset(arg, 0, sizeof(serial_icounter_struct));
        return 0;
    }
    std::atomic<std::uint64_t>& slot = slots[fd];
    const std::uint64_t fresh = std::uint64_t{key} << 32 | kInUse | kOutputLines;
    std::uint64_t old = slot.load(std::memory_order_relaxed);
    for (;;) {
        const bool mine = (old & kInUse) && (old >> 32) == key;
        const std::uint64_t current = mine ? old : fresh;
        const int lines = static_cast<int>(current & kOutputLines);
        int wanted = lines;
        switch (request) {
        case TIOCMGET:
            *static_cast<int*>(arg) = lines | kInputLines;
            break;
        case TIOCMSET:
            wanted = *static_cast<const int*>(arg) & static_cast<int>(kOutputLines);
            break;
        case TIOCMBIS:
            wanted = lines | (*static_cast<const int*>(arg) & static_cast<int>(kOutputLines));
            break;
        case TIOCMBIC:
            wanted = lines & ~*static_cast<const int*>(arg);
            break;
        default:
            break;
        }
        const std::uint64_t next =
            (current & ~kOutputLines) | static_cast<std::uint64_t>(wanted);
        if (next == old)
            return 0;
        if (slot.compare_exchange_weak(old, next, std::memory_order_relaxed))
            return 0;
    }
}

} // namespace

extern "C" {

/// ioctl(2) with emulated modem lines on pty slaves; everything else is the real ioctl.
__attribute__((visibility("default"))) int ioctl(int fd, unsigned long request, ...) noexcept
{
    // glibc: int ioctl(int, unsigned long, ...). Every request this shim cares about passes
    // a pointer; for the others the word is forwarded untouched.
    std::va_list ap;
    va_start(ap, request);
    void* arg = va_arg(ap, void*);
    va_end(ap);

    IoctlFn real = real_ioctl();
    if (!real) {
        errno = ENOSYS;
        return -1;
    }
    const int saved_errno = errno;
    const int result = real(fd, request, arg);
    if (result != -1 || errno != ENOTTY || !is_modem_request(request) || fd < 0 ||
        fd >= kSlots)
        return result;
    const std::uint32_t key = pty_slave_key(fd);
    if (key == 0) {
        errno = ENOTTY;
        return -1;
    }
    errno = saved_errno;
    return emulate(fd, key, request, arg);
}

/// close(2), forgetting the fd's emulated lines first (async-signal-safe: atomics only).
__attribute__((visibility("default"))) int close(int fd)
{
    if (fd >= 0 && fd < kSlots)
        slots[fd].store(0, std::memory_order_relaxed);
    CloseFn real = real_close();
    if (!real) {
        errno = ENOSYS;
        return -1;
    }
    return real(fd);
}

} // extern "C"
