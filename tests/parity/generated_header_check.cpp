#include "fixture_model.hpp"
#include "fixture_pca_model.hpp"

#include "actionstring/annotator.hpp"
#include "actionstring/storage.hpp"

// The model and its storage sizes are usable in constant expressions.
static_assert(fixture::kModel.component_count == 6, "the fixture has 6 components");
static_assert(fixture::kAnnotatorWithWindowsBytes > fixture::kAnnotatorBytes, "the window rule's state is extra");
actionstring::StateBuffer<fixture::kAnnotatorWithWindowsBytes> fixture_state;

static_assert(fixture_pca::kModel.component_count == 0 && fixture_pca::kModel.gmm_means == nullptr,
              "the second fixture has no GMM");
actionstring::StateBuffer<fixture_pca::kAnnotatorBytes> fixture_pca_state;
