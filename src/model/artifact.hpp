// actionstring host library — the model artifact.
//
// The artifact is text: a version line, a checksum line, then one line per
// field of the model schema (`name value`, or `name count values…` for a
// table), floats as C99 hexadecimal literals so every value round-trips
// exactly. Loading refuses a wrong version, a checksum that does not match,
// truncation, and tables the runtime would refuse.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "model/model_data.hpp"

namespace actionstring {
namespace host {

/// Artifact format version written and read by this build.
/// Version 2 added the input skeleton's joint names, 4 the label bounds, 5
/// the interleaved GMM factors, 6 the exemplars, 7 the acceleration's weight,
/// 8 the events' shortest action, 9 the exemplars' dimension, 10 the clip
/// descriptor, 11 the labels' lead, 12 the clip's motion directions, 13 the
/// early settling of stable labels (versions 4 to 12 are still read: 4's
/// factors reordered, 4 and 5 without exemplars, 4 to 6 without acceleration,
/// 4 to 7 with the shortest action the runtime's default, 250 ms, 4 to 8 with
/// exemplars of every feature coordinate, 4 to 9 without a clip descriptor,
/// all but 11 with labels at their characters' ticks, a lead of 0, 4 to 11
/// without the clip's motion directions, and all settling by the delay alone).
constexpr int artifact_version = 14;

/// 64-bit FNV-1a of the bytes.
std::uint64_t fnv1a64(std::string_view bytes);

/// The artifact text of a model (deterministic: same model, same bytes).
std::string serialize_model(const ModelData& model);
/// Parses artifact text; throws ReadError naming `name` and the line.
ModelData parse_model(const std::string& name, std::string_view text);

/// The fields alone, in schema order, without the version and checksum lines
/// and without checking that they make a valid model (tests walk the schema with it).
std::string serialize_fields(const ModelData& model);
/// Reads what serialize_fields() writes; checks syntax and ranges only.
ModelData parse_fields(const std::string& name, std::string_view fields);

void save_model(const ModelData& model, const std::string& path);
/// Reads a model file: an artifact, or a blob (`codegen --blob`).
ModelData load_model(const std::string& path);

/// The checksum recorded in an artifact's text, as 16 hex digits.
std::string artifact_checksum(std::string_view text);

}  // namespace host
}  // namespace actionstring
