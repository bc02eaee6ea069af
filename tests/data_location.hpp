// Where the shared datasets are: $ACTIONSTRING_DATA, else ../shared/data beside the checkout.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/stat.h>

namespace test {

inline std::string data_dir() {
    if (const char* env = std::getenv("ACTIONSTRING_DATA")) return env;
    return std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
}

/// True when `relative` exists under the data folder; otherwise says once, loudly, what is skipped.
inline bool have_data(const std::string& relative) {
    struct stat info {};
    if (stat((data_dir() + "/" + relative).c_str(), &info) == 0) return true;
    std::fprintf(stderr, "SKIPPED: %s not found under %s (set ACTIONSTRING_DATA to the datasets folder)\n",
                 relative.c_str(), data_dir().c_str());
    return false;
}

}  // namespace test
