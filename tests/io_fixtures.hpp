// Scratch files of the io tests (test_io.cpp, test_io_csv.cpp, test_io_options.cpp): a path in the
// running test's scratch directory, a whole file, its first line.
#pragma once

#include "scratch_dir.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pd_test {

// A path in this test's scratch directory; its parent directory exists.
inline std::string temp_path(const std::string& name)
{
    const auto p = scratch_dir() / name;
    std::filesystem::create_directories(p.parent_path());
    return p.string();
}

inline std::string slurp(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline std::string first_line(const std::string& path)
{
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

}  // namespace pd_test
