#include "report/ReconstructSettings.hpp"

#include <algorithm>
#include <stdexcept>

#include "report/EnumNames.hpp"
#include "report/MeshFormatOption.hpp"
#include "report/NumberChecks.hpp"
#include "simplify/Simplification.hpp"

namespace dfrecon {

void addReconstructSettingsOptions(CLI::App& cmd, ReconstructSettings& settings) {
    ReconstructionOptions& options = settings.options;
    cmd.add_option("--pixel-mm", options.pixelMm,
                   "Field pixel size in mm (default 0: the ROI's extent plus margin fits 256 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd.add_option("--contour-error", options.contourErrorMm,
                   "Simplify contours first so every original point stays within this many mm "
                   "(0 = keep every point)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd.add_option("--max-depth", options.maxDepth,
                   "Recursion levels for branching regions; at the limit what is left is closed "
                   "by a step of spacing / 2^(depth+1)")
        ->capture_default_str()
        ->check(CLI::Range(0, 12));
    cmd.add_option_function<std::string>(
           "--cap",
           [&options](const std::string& name) {
               options.cap = parseEnum(kCapModeNames, name, "--cap");
           },
           "End caps: flat, dome or none")
        ->default_str(nameOf(kCapModeNames, options.cap))
        ->check(CLI::IsMember(namesOf(kCapModeNames)));
    cmd.add_option_function<std::string>(
           "--interpolation",
           [&options](const std::string& name) {
               options.interpolation = parseEnum(kInterpolationNames, name, "--interpolation");
           },
           "Between planes: 'smooth' bends the strips onto a cubic in z of the planes' "
           "distance fields (C1 across planes, bulging where the anatomy does) and "
           "brings each slab's volume to the C1 integral of its planes' areas, still "
           "through every contour point and a valid solid (a place where bending would "
           "break it stays straight); 'linear' runs straight from contour to contour "
           "(smaller: straight strips cut inside curved anatomy)")
        ->default_str(nameOf(kInterpolationNames, options.interpolation))
        ->check(CLI::IsMember(namesOf(kInterpolationNames)));
    cmd.add_option("--smooth-tolerance", options.smoothToleranceMm,
                   "Smooth mode: strips are halved in z (down to a quarter of the slab) until "
                   "no straight edge strays farther than this from the smooth surface, mm")
        ->capture_default_str()
        ->check(kPositive);
    cmd.add_option("--cap-offset", options.capOffsetMm,
                   "How far beyond an end contour its cap reaches, mm (default: half the DICOM "
                   "contour slab thickness if given, else half the slice spacing; at most half "
                   "the gap to the next slice; at most 1000: a cap a metre beyond its contour "
                   "is no anatomy, and beyond that it is no valid solid)")
        ->check(numberCheck([](double v) { return v >= 0 && v <= 1000; },
                            "must be from 0 to 1000 mm", "0 <= NUMBER <= 1000"));
    cmd.add_option("--max-error", settings.maxErrorMm,
                   "Then simplify with this two-sided bound in mm, as dfrecon simplify does "
                   "(0 = keep every triangle; else at least 1e-6 mm, below which coordinates do "
                   "not resolve the bound); the report gives the certified bound and the "
                   "verified distance to the full surface and the contours")
        ->capture_default_str()
        ->check(maxErrorCheck(kMinMaxErrorMm, true));
    cmd.add_flag("--allow-invalid", settings.allowInvalid,
                 "Write a surface that is not a valid closed solid anyway (it is reported, "
                 "and the exit code is still 4)");
    cmd.add_flag("--ascii", settings.ascii, "ASCII PLY/STL instead of binary");
    addMeshFormatOption(cmd, settings.format,
                        "Mesh format where no file extension names one: -o - (standard output, "
                        "required there) and the per-ROI files written into a folder (--all, "
                        "batch; default ply); a -o file's extension decides, and --format must "
                        "agree with it");
}

MeshFormat ReconstructSettings::folderFormat() const {
    return meshFormatNamed(format).value_or(MeshFormat::Ply);
}

std::vector<std::string> reconstructSettingsNames() {
    ReconstructSettings settings;
    CLI::App app;
    addReconstructSettingsOptions(app, settings);
    std::vector<std::string> names;
    for (const CLI::Option* option : app.get_options())
        if (!option->get_lnames().empty() && option->get_lnames().front() != "help")
            names.push_back(option->get_lnames().front());
    return names;
}

ReconstructSettings withGivenOptions(const ReconstructSettings& base,
                                     const std::vector<GivenOption>& given) {
    ReconstructSettings settings = base;
    for (const GivenOption& option : given) {
        // A fresh parser per option, so each message names its own option
        // and nothing of one parse carries into the next.
        CLI::App app;
        addReconstructSettingsOptions(app, settings);
        const std::string where = option.where.empty() ? "" : option.where + ": ";
        static const std::vector<std::string> known = reconstructSettingsNames();
        if (std::find(known.begin(), known.end(), option.name) == known.end())
            throw std::invalid_argument(where + "unknown option '" + option.name + "'");
        std::vector<std::string> args{"--" + option.name + "=" + option.value};
        try {
            app.parse(args);
        } catch (const CLI::ParseError& e) {  // its message names the option
            throw std::invalid_argument(where + e.what());
        }
    }
    return settings;
}

nlohmann::ordered_json reconstructSettingsJson(const ReconstructSettings& settings) {
    const ReconstructionOptions& o = settings.options;
    return {{"pixel-mm", o.pixelMm},
            {"contour-error", o.contourErrorMm},
            {"max-depth", o.maxDepth},
            {"cap", nameOf(kCapModeNames, o.cap)},
            {"interpolation", nameOf(kInterpolationNames, o.interpolation)},
            {"smooth-tolerance", o.smoothToleranceMm},
            {"cap-offset", o.capOffsetMm < 0 ? nlohmann::ordered_json(nullptr)
                                             : nlohmann::ordered_json(o.capOffsetMm)},
            {"max-error", settings.maxErrorMm},
            {"allow-invalid", settings.allowInvalid},
            {"ascii", settings.ascii},
            {"format", meshFormatName(settings.folderFormat())}};
}

}  // namespace dfrecon
