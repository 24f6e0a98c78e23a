#pragma once
// Files the daemon writes for others to read (--endpoints-json, --state-file): replaced
// whole or not at all, never through a link planted at a predictable temporary name.

#include <string>
#include <vector>

namespace rigsim {

/// Write `text` to `path` atomically: a new temporary file beside it (O_EXCL|O_NOFOLLOW,
/// name `<path>.tmp<pid>.<random>`), fsync, rename over `path`, fsync of the directory. A
/// symlink at `path` is followed: its target is replaced and the link stays. Throws
/// std::system_error naming the file; the temporary file is removed on failure.
void write_file_atomically(const std::string& path, const std::string& text);

/// `path` with symlinks in its last component followed (up to 40 hops; a dangling link gives
/// the missing target): the file a write through `path` replaces. Throws std::system_error.
std::string resolve_symlinks(const std::string& path);

/// Remove the temporary files write_file_atomically left beside `path` when it was killed
/// (`<path>.tmp<pid>` or `<path>.tmp<pid>.<suffix>` whose pid is no running process).
/// Returns the paths removed.
std::vector<std::string> remove_stale_temporaries(const std::string& path);

/// Create a file that does not exist yet, `base`, else `base.1`, `base.2`, ... (O_EXCL,
/// never through a link), with `text`, synced. Returns its path; throws std::system_error.
std::string write_new_file(const std::string& base, const std::string& text);

} // namespace rigsim
