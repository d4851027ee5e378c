// A scratch directory private to the running test: CTest runs every GoogleTest case as its own
// process, in parallel, so fixed names under TempDir() would be shared between concurrent tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace pd_test {

inline std::filesystem::path scratch_dir()
{
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "no_test";
    const auto dir = std::filesystem::path(::testing::TempDir()) /
                     ("pd_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace pd_test
