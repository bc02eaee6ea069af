// actionstring host library — clips joined into one stream, for replay on a
// device (firmware, C API tests) and for online evaluation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/clip.hpp"

namespace actionstring {
namespace host {

/// One clip of a replay stream and the label it is known to show.
struct StreamSegment {
    const Clip* clip = nullptr;  ///< Borrowed: must outlive the call.
    std::string label;
    double max_seconds = 0.0;  ///< Keep at most this much of the clip; 0 keeps all of it.
};

/// Clips joined into one stream: each starts one frame period after the
/// previous one ends, so the times never jump or go back.
struct ConcatenatedStream {
    std::size_t joints = 0;
    std::vector<std::int64_t> times_us;  ///< Per frame.
    std::vector<float> positions;        ///< frames × joints × xyz, metres.
    std::vector<std::uint32_t> segment_first_frame;
    std::vector<std::string> segment_labels;
    std::size_t frame_count() const noexcept { return times_us.size(); }
    const float* frame(std::size_t f) const noexcept { return positions.data() + f * joints * 3; }
};
/// Throws std::invalid_argument for no frames or clips of different skeletons.
ConcatenatedStream concatenate_stream(const std::vector<StreamSegment>& segments);

/// A header of constexpr tables holding `segments` concatenated into one
/// stream (times in µs, positions in metres, exactly as read), for a firmware
/// to replay. `command` is recorded in the DO-NOT-EDIT banner.
std::string generate_stream_header(const std::vector<StreamSegment>& segments, const std::string& ns,
                                   const std::string& command);

/// The same stream as text: one line per frame, the time in µs then the
/// coordinates as C99 hexadecimal floats (exact), for programs in other languages.
std::string generate_stream_text(const std::vector<StreamSegment>& segments);

}  // namespace host
}  // namespace actionstring
