// Writes the fuzz_model seeds: the toy world's model artifact, whole and as a
// bare body (which the target gives a valid checksum), with full and diagonal
// covariance, and one with the characters' votes; with BLOB_DIR also the fuzz_blob seeds, the same models as blobs.
//   actionstring_fuzz_model_seed OUT_DIR [BLOB_DIR]
#include <cmath>
#include <cstdio>
#include <string>

#include "io/text.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "toy/toy.hpp"

int main(int argc, char** argv) {
    using namespace actionstring::host;
    if (argc != 2 && argc != 3) {
        std::fprintf(stderr, "usage: actionstring_fuzz_model_seed OUT_DIR [BLOB_DIR]\n");
        return 2;
    }
    const std::string out = argv[1];
    ToyOptions diagonal;
    diagonal.covariance = actionstring::Covariance::diagonal;
    for (const auto& [name, options] : {std::pair<const char*, ToyOptions>{"full", {}}, {"diagonal", diagonal}}) {
        const ToyWorld world = make_toy_world(options);
        const std::string text = serialize_model(world.model);
        write_file(out + "/" + name + ".model", text);
        write_file(out + "/" + name + "_body.txt", serialize_fields(world.model));
        if (argc == 3) write_file(std::string(argv[2]) + "/" + name + ".blob", write_blob(world.model));
    }
    // With the characters' votes (uniform: every character equally likely under every label and
    // under no action).
    ToyWorld voting = make_toy_world();
    voting.model.vote_weight = 1.0f;
    voting.model.character_votes.assign(voting.model.label_names.size() * voting.model.character_count,
                                        -std::log(static_cast<float>(voting.model.character_count)));
    voting.model.has_no_action_votes = 1;
    voting.model.no_action_votes.assign(voting.model.character_count,
                                        -std::log(static_cast<float>(voting.model.character_count)));
    write_file(out + "/votes.model", serialize_model(voting.model));
    write_file(out + "/votes_body.txt", serialize_fields(voting.model));
    if (argc == 3) write_file(std::string(argv[2]) + "/votes.blob", write_blob(voting.model));
    return 0;
}
