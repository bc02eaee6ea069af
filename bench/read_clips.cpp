// Reading + forward kinematics speed on the clips of one or more clip lists.
//
//   actionstring_read_clips [LIST ...]     (default: hdm05/train.tsv and val.tsv
//                                           under $ACTIONSTRING_DATA or ../shared/data)
// Single-threaded. Prints the median of 5 timed passes after one warm-up pass.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/clip_list.hpp"
#include "io/formats.hpp"

using namespace actionstring::host;

int main(int argc, char** argv) {
    std::vector<std::string> lists;
    for (int i = 1; i < argc; ++i) lists.push_back(argv[i]);
    if (lists.empty()) {
        const char* env = std::getenv("ACTIONSTRING_DATA");
        const std::string data = env != nullptr ? env : std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
        lists = {data + "/hdm05/train.tsv", data + "/hdm05/val.tsv"};
    }
    std::vector<ClipListEntry> entries;
    try {
        for (const auto& list : lists) {
            const auto part = read_clip_list(list);
            entries.insert(entries.end(), part.begin(), part.end());
        }
    } catch (const ReadError& error) {
        std::fprintf(stderr, "SKIPPED: %s (set ACTIONSTRING_DATA or pass clip lists)\n", error.what());
        return 0;
    }
    std::vector<double> seconds;
    std::size_t frames = 0;
    for (int pass = 0; pass < 6; ++pass) {
        frames = 0;
        const auto begin = std::chrono::steady_clock::now();
        for (const auto& entry : entries) frames += read_clip(entry).frame_count();
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - begin;
        if (pass > 0) seconds.push_back(elapsed.count());
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("read + FK: %zu clips, %zu frames: median %.3f s (min %.3f, max %.3f) over 5 passes, %.2f us/frame\n",
                entries.size(), frames, seconds[2], seconds.front(), seconds.back(),
                seconds[2] * 1e6 / static_cast<double>(frames));
    return 0;
}
