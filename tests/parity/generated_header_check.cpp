#include "fixture_model.hpp"

#include "actionstring/annotator.hpp"

// The model is usable in constant expressions, and its capacity fits it.
static_assert(fixture::kModel.component_count == 6, "the fixture has 6 components");
static_assert(fixture::ModelCapacity::fits(fixture::kModel), "ModelCapacity fits its model");
actionstring::Annotator<fixture::ModelCapacity> fixture_annotator;
