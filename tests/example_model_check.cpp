// The committed example model header compiles on its own and drives the
// runtime: built for the host (no exceptions, no RTTI) and, when
// arm-none-eabi-g++ is installed, for a Cortex-M4F.
#include "hdm05_model.hpp"

#include "actionstring/annotator.hpp"
#include "actionstring/storage.hpp"

static_assert(actionstring_hdm05::kModel.joint_count == 31, "an HDM05 skeleton");
// The storage sizes are constants a static array can take.
static_assert(actionstring_hdm05::kAnnotatorBytes > 0 &&
                  actionstring_hdm05::kAnnotatorBytes < actionstring_hdm05::kAnnotatorWithWindowsBytes,
              "the window rule's state is extra");

actionstring::Annotator example_model_annotator;
actionstring::StateBuffer<actionstring_hdm05::kAnnotatorBytes> example_model_state;

bool example_model_accepted() {
    return example_model_annotator.init(actionstring_hdm05::kModel,
                                        actionstring::annotator_config(actionstring_hdm05::kModel),
                                        example_model_state.data(), example_model_state.size()) ==
           actionstring::Status::ok;
}
