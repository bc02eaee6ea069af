// actionstring host library — how a file is named to a reader of a page or report.
#pragma once

#include <filesystem>
#include <string>

namespace actionstring {
namespace host {

/// The last two components of a path ("msr-action3d/test.tsv"): enough to tell
/// one dataset's list from another's, without the machine's own folders, for
/// titles of pages and reports that are shared.
inline std::string short_path(const std::string& path) {
    const std::filesystem::path p(path);
    const std::filesystem::path parent = p.parent_path().filename();
    if (parent.empty() || parent == "." || parent == "..") return p.filename().string();
    return (parent / p.filename()).string();
}

}  // namespace host
}  // namespace actionstring
