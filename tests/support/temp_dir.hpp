#pragma once
// A fresh directory for unit and device tests that touch files, removed with what it holds
// (files, and empty subdirectories) when the test ends; plus whole-file read and write.

#include <catch2/catch.hpp>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rigsim::test {

class TempDir {
public:
    TempDir()
    {
        char t[] = "/tmp/rigsim-test-XXXXXX";
        REQUIRE(::mkdtemp(t));
        path_ = t;
    }
    ~TempDir()
    {
        for (const auto& name : entries()) {
            const auto p = file(name);
            if (::unlink(p.c_str()) != 0)
                ::rmdir(p.c_str());
        }
        ::rmdir(path_.c_str());
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::string& path() const { return path_; }
    /// `path()/name`.
    std::string file(const std::string& name) const { return path_ + "/" + name; }
    /// The names in the directory, sorted, without "." and "..".
    std::vector<std::string> entries() const
    {
        std::vector<std::string> names;
        if (DIR* d = ::opendir(path_.c_str())) {
            while (const dirent* e = ::readdir(d))
                if (std::string(e->d_name) != "." && std::string(e->d_name) != "..")
                    names.push_back(e->d_name);
            ::closedir(d);
        }
        std::sort(names.begin(), names.end());
        return names;
    }

private:
    std::string path_;
};

/// The whole content of `path` ("" if it cannot be read).
inline std::string read(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Replace the content of `path` with `text`.
inline void write(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
}

} // namespace rigsim::test
