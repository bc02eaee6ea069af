// Writes the fuzz_model seeds: the toy world's model artifact, whole and as a
// bare body (which the target gives a valid checksum), with full and diagonal
// covariance; with BLOB_DIR also the fuzz_blob seeds, the same models as blobs.
//   actionstring_fuzz_model_seed OUT_DIR [BLOB_DIR]
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
    return 0;
}
