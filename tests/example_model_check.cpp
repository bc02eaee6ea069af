// The committed example model header compiles on its own and drives the
// runtime: built for the host (no exceptions, no RTTI) and, when
// arm-none-eabi-g++ is installed, for a Cortex-M4F.
#include "hdm05_model.hpp"

#include "actionstring/annotator.hpp"

static_assert(actionstring_hdm05::ModelCapacity::fits(actionstring_hdm05::kModel), "ModelCapacity fits the model");
static_assert(actionstring_hdm05::kModel.joint_count == 31, "an HDM05 skeleton");

actionstring::Annotator<actionstring_hdm05::ModelCapacity> example_model_annotator;

bool example_model_accepted() {
    return example_model_annotator.init(actionstring_hdm05::kModel) == actionstring::Status::ok;
}
