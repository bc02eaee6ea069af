// actionstring host library — the model blob: the binary form the runtime
// reads in place (include/actionstring/blob.hpp describes the layout).
#pragma once

#include <string>
#include <string_view>

#include "model/model_data.hpp"

namespace actionstring {
namespace host {

/// The model as a blob (deterministic: same model, same bytes). Throws
/// ReadError for a model the runtime would refuse, as the header generator does.
std::string write_blob(const ModelData& model);

/// An owning copy of the model in a blob, checked by the runtime's own reader
/// (model_from_blob); throws ReadError naming `name` and what is wrong.
ModelData read_blob(const std::string& name, std::string_view bytes);

/// Whether the bytes start like a blob (so a tool can take either form).
bool looks_like_blob(std::string_view bytes);

}  // namespace host
}  // namespace actionstring
