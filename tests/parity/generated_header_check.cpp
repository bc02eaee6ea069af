#include "fixture_model.hpp"
#include "fixture_pca_model.hpp"

#include "actionstring/annotator.hpp"

// The model is usable in constant expressions, and its capacity fits it.
static_assert(fixture::kModel.component_count == 6, "the fixture has 6 components");
static_assert(fixture::ModelCapacity::fits(fixture::kModel), "ModelCapacity fits its model");
actionstring::Annotator<fixture::ModelCapacity> fixture_annotator;

static_assert(fixture_pca::kModel.component_count == 0 && fixture_pca::kModel.gmm_means == nullptr,
              "the second fixture has no GMM");
static_assert(fixture_pca::ModelCapacity::fits(fixture_pca::kModel), "ModelCapacity fits its model");
actionstring::Annotator<fixture_pca::ModelCapacity> fixture_pca_annotator;
