// actionstring — command line front end.
#include <cstdio>
#include <cstring>

#include "actionstring/version.hpp"
#include "commands.hpp"

namespace {

void print_usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: actionstring <command> [options]\n"
                 "\n"
                 "commands:\n"
                 "  demo       stream a synthetic performance through the runtime and print\n"
                 "             the label timeline (no data needed)\n"
                 "  train      train a model from a clip list and write the model artifact\n"
                 "  codegen    turn a model artifact into a header of constexpr tables\n"
                 "  eval       clip accuracy of a model on a list, beside baselines\n"
                 "  annotate   the label timeline of a recording (TSV or JSON)\n"
                 "  view       a self-contained HTML page to watch a recording with its labels\n"
                 "  stream-table  write clips of a list as one replay stream of constexpr\n"
                 "             tables (for the firmware, port/firmware)\n"
                 "  interval-list  a continuous dataset's timeline (UTKinect) as a clip list of\n"
                 "             labelled intervals, for train and eval --online\n"
                 "  info       describe a motion file: joints, frames, duration, rate, bounds\n"
                 "  version    print the library version\n"
                 "\n"
                 "Run 'actionstring <command> --help' for a command's options.\n");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        print_usage(stderr);
        return 2;
    }
    const char* command = argv[1];
    if (std::strcmp(command, "--help") == 0 || std::strcmp(command, "-h") == 0 || std::strcmp(command, "help") == 0) {
        print_usage(stdout);
        return 0;
    }
    if (std::strcmp(command, "version") == 0 || std::strcmp(command, "--version") == 0) {
        std::printf("actionstring %s\n", actionstring::version_string());
        return 0;
    }
    if (std::strcmp(command, "demo") == 0) return actionstring::cli::run_demo(argc - 1, argv + 1);
    if (std::strcmp(command, "info") == 0) return actionstring::cli::run_info(argc - 1, argv + 1);
    if (std::strcmp(command, "train") == 0) return actionstring::cli::run_train(argc - 1, argv + 1);
    if (std::strcmp(command, "codegen") == 0) return actionstring::cli::run_codegen(argc - 1, argv + 1);
    if (std::strcmp(command, "eval") == 0) return actionstring::cli::run_eval(argc - 1, argv + 1);
    if (std::strcmp(command, "stream-table") == 0) return actionstring::cli::run_stream_table(argc - 1, argv + 1);
    if (std::strcmp(command, "interval-list") == 0) return actionstring::cli::run_interval_list(argc - 1, argv + 1);
    if (std::strcmp(command, "annotate") == 0) return actionstring::cli::run_annotate(argc - 1, argv + 1);
    if (std::strcmp(command, "view") == 0) return actionstring::cli::run_view(argc - 1, argv + 1);
    std::fprintf(stderr, "actionstring: unknown command '%s'\n\n", command);
    print_usage(stderr);
    return 2;
}
