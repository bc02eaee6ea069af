// Clip accuracy and online frame accuracy from a generated header's constexpr
// model (the tables a device compiles in), with the same evaluation code as
// `actionstring eval`, as one JSON object on stdout.   actionstring_header_eval LIST
#include <cstdio>
#include <exception>

#include "common/json.hpp"
#include "eval/clip_eval.hpp"
#include "eval/online.hpp"
#include "io/clip_list.hpp"
#include "run/skeleton.hpp"
#include ACTIONSTRING_MODEL_HEADER

int main(int argc, char** argv) {
    namespace host = actionstring::host;
    if (argc != 2) {
        std::fprintf(stderr, "usage: actionstring_header_eval LIST\n");
        return 2;
    }
    try {
        const actionstring::ModelView& model = ACTIONSTRING_MODEL_NAMESPACE::kModel;
        std::vector<host::LabelledClip> clips = host::load_labelled_clips(argv[1]);
        host::conform_to_model(model, clips);
        const auto clip_results = host::evaluate_model(model, clips);
        const auto online = host::evaluate_online(model, clips, 1);
        host::JsonWriter out;
        out.begin_object()
            .field("model_checksum", ACTIONSTRING_MODEL_NAMESPACE::kModelChecksum)
            .field("clips", clips.size())
            .field("clip_accuracy", clip_results.clip_accuracy)
            .field("online_frame_accuracy", online.settled.frame_accuracy)
            .end_object();
        std::fputs(out.str().c_str(), stdout);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "actionstring_header_eval: %s\n", error.what());
        return 1;
    }
}
