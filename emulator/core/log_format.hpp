#pragma once
// spdlog for a file that logs with arguments (`log.info("{}: ...", peer)`). spdlog formats its
// arguments with fmt's engine, detail::vformat_to<char>, a template that every file using it would
// instantiate and optimise again (a single such call cost 2.4 s of GCC -O3 per translation
// unit). Debian's libfmt exports that instantiation, so this file declares it extern: the
// engine is compiled once, in libfmt, and every log line formats exactly as before.
// GCC only: GCC built Debian's libfmt, and clang mangles this function's signature otherwise (a
// dependent std::is_same in it: "sr3std" against GCC's "srSt"), so a clang build would find no
// such symbol in libfmt and instantiates the engine itself, as without this file.

#include <spdlog/spdlog.h>

#if defined(__GNUC__) && !defined(__clang__) && defined(SPDLOG_FMT_EXTERNAL) && !defined(FMT_HEADER_ONLY) \
    && FMT_VERSION >= 90000 && FMT_VERSION < 100000
extern template void fmt::detail::vformat_to<char>(fmt::detail::buffer<char>&, fmt::basic_string_view<char>,
                                                   fmt::basic_format_args<fmt::buffer_context<fmt::type_identity_t<char>>>,
                                                   fmt::detail::locale_ref);
#endif
