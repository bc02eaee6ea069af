// actionstring host library — a model as a C++ header of constexpr tables.
#pragma once

#include <string>

#include "model/model_data.hpp"

namespace actionstring {
namespace host {

/// A C++17 header of constexpr tables for `model`: a DO-NOT-EDIT banner with
/// the artifact's checksum, one array per table of the model schema, `kModel`
/// (a ModelView), `kAnnotatorBytes` and `kAnnotatorWithWindowsBytes` (the
/// Annotator's exact storage for it) and `kModelChecksum`, in namespace `ns`. Throws
/// std::invalid_argument for a model that fails validation or a namespace
/// that is not a C++ namespace name.
std::string generate_header(const ModelData& model, const std::string& checksum, const std::string& ns,
                            const std::string& source_name);

}  // namespace host
}  // namespace actionstring
