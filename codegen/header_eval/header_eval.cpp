// Clip accuracy and online frame accuracy from a generated header's constexpr
// model (the tables a device compiles in), with the same evaluation code as
// `actionstring eval`.   actionstring_header_eval LIST
#include <cstdio>
#include <exception>

#include "actionstring_host/evaluation.hpp"
#include "actionstring_host/readers.hpp"
#include ACTIONSTRING_MODEL_HEADER

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: actionstring_header_eval LIST\n");
        return 2;
    }
    try {
        std::vector<actionstring::host::LabelledClip> clips;
        for (const auto& entry : actionstring::host::read_clip_list(argv[1]))
            clips.push_back({actionstring::host::read_clip(entry), entry.label, entry.subject});
        const actionstring::ModelView& model = ACTIONSTRING_MODEL_NAMESPACE::kModel;
        const auto clip_results = actionstring::host::evaluate_model(model, clips);
        const auto online = actionstring::host::evaluate_online(model, clips, 1);
        std::printf("model %s: clip accuracy %.3f online frame accuracy %.3f\n", ACTIONSTRING_MODEL_NAMESPACE::kModelChecksum,
                    clip_results.clip_accuracy, online.settled.frame_accuracy);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "actionstring_header_eval: %s\n", error.what());
        return 1;
    }
}
