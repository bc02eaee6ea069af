// Writes the fuzz_model seeds: the toy world's model artifact, whole and as a
// bare body (which the target gives a valid checksum), with full and diagonal
// covariance, one with the characters' votes and one with a clip descriptor; with BLOB_DIR also the
// fuzz_blob seeds, the same models as blobs.
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
    // With a clip descriptor (two levels over three coordinates; weights small and varied), so
    // the fuzzers reach its fields and the sizes its tables derive from them.
    ToyWorld described = make_toy_world();
    described.model.descriptor_weight = 1.0f;
    described.model.descriptor_levels = 2;
    described.model.descriptor_dim = 3;
    const std::size_t size = described.model.view().descriptor_size();
    for (std::size_t k = 0; k < described.model.label_names.size() * size; ++k)
        described.model.descriptor_weights.push_back(static_cast<float>(k % 7) * 0.125f - 0.375f);
    described.model.descriptor_bias.assign(described.model.label_names.size(), 0.5f);
    write_file(out + "/descriptor.model", serialize_model(described.model));
    write_file(out + "/descriptor_body.txt", serialize_fields(described.model));
    if (argc == 3) write_file(std::string(argv[2]) + "/descriptor.blob", write_blob(described.model));
    // With motion directions (two levels over the toy's pose joints), likewise.
    ToyWorld directed = make_toy_world();
    directed.model.direction_weight = 1.0f;
    directed.model.direction_levels = 2;
    const std::size_t histograms = directed.model.view().direction_size();
    for (std::size_t k = 0; k < directed.model.label_names.size() * histograms; ++k)
        directed.model.direction_weights.push_back(static_cast<float>(k % 5) * 0.25f - 0.5f);
    directed.model.direction_bias.assign(directed.model.label_names.size(), -0.25f);
    write_file(out + "/directions.model", serialize_model(directed.model));
    write_file(out + "/directions_body.txt", serialize_fields(directed.model));
    if (argc == 3) write_file(std::string(argv[2]) + "/directions.blob", write_blob(directed.model));
    return 0;
}
