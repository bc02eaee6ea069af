// actionstring host library — the model artifact and the constexpr header generator.
//
// The artifact is text: a version line, a checksum line, then one line per
// table (`name count values…`), floats as C99 hexadecimal literals so every
// value round-trips exactly. Loading refuses a wrong version, a checksum that
// does not match, truncation, and tables the runtime would refuse.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "actionstring_host/clip.hpp"
#include "actionstring_host/model_data.hpp"

namespace actionstring {
namespace host {

/// Artifact format version written and read by this build.
constexpr int artifact_version = 1;

/// 64-bit FNV-1a of the bytes.
std::uint64_t fnv1a64(std::string_view bytes);

/// The artifact text of a model (deterministic: same model, same bytes).
std::string serialize_model(ModelData& model);
/// Parses artifact text; throws ReadError naming `name` and the line.
ModelData parse_model(const std::string& name, std::string_view text);

void save_model(ModelData& model, const std::string& path);
ModelData load_model(const std::string& path);

/// The checksum recorded in an artifact's text, as 16 hex digits.
std::string artifact_checksum(std::string_view text);

/// A C++17 header of constexpr tables for `model`: a DO-NOT-EDIT banner with
/// the artifact's checksum, `kModel` (a ModelView), `ModelCapacity` (a
/// Capacity that fits exactly) and `kModelChecksum`, in namespace `ns`.
std::string generate_header(ModelData& model, const std::string& checksum, const std::string& ns,
                            const std::string& source_name);

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
    std::vector<long long> times_us;              ///< Per frame.
    std::vector<float> positions;                 ///< frames × joints × xyz, metres.
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
