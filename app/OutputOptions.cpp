#include "app/OutputOptions.hpp"

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/StandardStreams.hpp"
#include "io/files/OutputTarget.hpp"

namespace dfrecon::app {

namespace fs = std::filesystem;

namespace {

// Options are made once per process, by the program, before any thread.
std::map<const CLI::Option*, OutputKind>& outputKinds() {
    static std::map<const CLI::Option*, OutputKind> kinds;
    return kinds;
}

struct Given {
    std::string option;  // its name, for messages
    std::string path;
    OutputKind kind = OutputKind::File;
};

bool isFile(const std::string& path) {
    std::error_code error;
    return fs::exists(path, error) && !fs::is_directory(path, error);
}

void refuse(const Given& output, const std::string& why) {
    throw std::invalid_argument(output.option + " " + output.path + ": " + why);
}

// The rule for one output on its own.
void checkKind(const Given& output) {
    const std::string why = whyNotAFileTarget(output.path);
    std::error_code error;
    const bool folder = fs::is_directory(output.path, error);
    if (output.kind == OutputKind::File && !why.empty())
        refuse(output, "refused as an output: " + why + " (give a file name)");
    if (output.kind != OutputKind::File && !why.empty() && !folder)
        refuse(output, "refused as an output: " + why);
    if (output.kind == OutputKind::Folder && isFile(output.path))
        refuse(output, "refused as an output folder: it is a file");
}

}  // namespace

CLI::Option* asOutput(CLI::Option* option, OutputKind kind) {
    outputKinds()[option] = kind;
    return option;
}

void checkOutputOptions(const CLI::App& command, const CLI::App& root) {
    std::vector<Given> outputs, inputs;
    for (const CLI::App* app : {&command, &root})
        for (const CLI::Option* option : app->get_options()) {
            if (option->count() == 0) continue;
            const auto marked = outputKinds().find(option);
            for (const std::string& value : option->results()) {
                if (value.empty() || isStandardStream(value)) continue;
                const Given given{
                    option->get_name(), value,
                    marked == outputKinds().end() ? OutputKind::File : marked->second};
                if (marked != outputKinds().end())
                    outputs.push_back(given);
                else if (isFile(value))
                    inputs.push_back(given);
            }
        }
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        checkKind(outputs[i]);
        for (const Given& input : inputs)
            if (sameFile(outputs[i].path, input.path))
                refuse(outputs[i],
                       "refused as an output: it is the input " + input.path +
                           (input.option.rfind("-", 0) == 0 ? " (" + input.option + ")" : "") +
                           ", which writing it would replace");
        for (std::size_t j = 0; j < i; ++j) {
            if (sameFile(outputs[i].path, outputs[j].path))
                refuse(outputs[i], "the same file as " + outputs[j].option + " " + outputs[j].path +
                                       ": each output needs a path of its own");
            if (sameFileIgnoringCase(outputs[i].path, outputs[j].path))
                refuse(outputs[i], "the same file as " + outputs[j].option + " " + outputs[j].path +
                                       " on file systems that ignore letter case: give names "
                                       "that differ in more than case");
        }
    }
}

}  // namespace dfrecon::app
