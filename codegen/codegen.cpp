// `actionstring codegen`: a model artifact as a header of constexpr tables.
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "common/cpp_literals.hpp"
#include "io/text.hpp"
#include "model/artifact.hpp"
#include "model/blob.hpp"
#include "model/header.hpp"
#include "options.hpp"

namespace actionstring {
namespace cli {

int run_codegen(int argc, char** argv) {
    std::string model_path, out_path, blob_path, ns = "actionstring_model";
    ArgumentReader args("codegen", argc, argv);
    while (args.more()) {
        const std::string arg = args.next();
        if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: actionstring codegen MODEL [--out HEADER [--namespace NS]] [--blob BLOB]\n\n"
                "--out writes a C++17 header of constexpr tables for MODEL: NS::kModel (a ModelView),\n"
                "NS::kAnnotatorBytes (the Annotator's exact storage for it) and NS::kModelChecksum, under a\n"
                "DO-NOT-EDIT banner carrying the artifact's checksum. [namespace: actionstring_model]\n"
                "--blob writes the model as a binary blob the runtime reads in place at run time\n"
                "(model_from_blob, the C API's actionstring_model_from_blob): versioned, checksummed,\n"
                "little-endian, every table aligned to 16 bytes.\n");
            return 0;
        }
        if (arg == "--out") out_path = args.value(arg);
        else if (arg == "--blob") blob_path = args.value(arg);
        else if (arg == "--namespace") ns = args.value(arg);
        else if (!arg.empty() && arg[0] == '-') return args.unknown(arg);
        else if (model_path.empty()) model_path = arg;
        else return args.error("more than one MODEL given");
    }
    if (!args.ok()) return 2;
    if (model_path.empty() || (out_path.empty() && blob_path.empty()))
        return args.error("usage: actionstring codegen MODEL [--out HEADER [--namespace NS]] [--blob BLOB]");
    if (!host::is_cpp_namespace(ns))
        return args.error("--namespace must be a C++ namespace name (identifiers joined by ::)");
    return run_reporting_errors("codegen", [&] {
        const std::string text = host::read_file(model_path);
        host::ModelData model = host::parse_model(model_path, text);
        if (!out_path.empty()) {
            const std::size_t slash = model_path.find_last_of('/');
            const std::string header =
                host::generate_header(model, host::artifact_checksum(text), ns,
                                      slash == std::string::npos ? model_path : model_path.substr(slash + 1));
            host::write_file(out_path, header);
        }
        if (!blob_path.empty()) host::write_file(blob_path, host::write_blob(model));
        return 0;
    });
}

}  // namespace cli
}  // namespace actionstring
