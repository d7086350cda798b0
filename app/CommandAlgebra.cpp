// dfrecon margin and dfrecon combine: a new ROI from the structure set's
// ROIs (dfrecon/Algebra: exact margins and Booleans against the
// reconstructed surfaces), written as contours on planes into the
// structure set (.slices or RTSTRUCT), and optionally as a mesh.
#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/RoiReconstruction.hpp"
#include "app/StandardStreams.hpp"
#include "dfrecon/Algebra.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/contours/RoiName.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/JsonText.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/ExitCodes.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

struct AlgebraArgs {
    std::string input, output, mesh, like, colour, roiType, name;
    double stepMm = 0.25, meshVoxelMm = 0.5, minAreaMm2 = 1e-4;
    bool json = false, onlyNew = false, replace = false, reference = false;
    // margin
    std::string roi, perDirection;
    double mm = 0;
    bool mmGiven = false;
    // combine
    std::string expression;
};

std::vector<double> numberList(const std::string& text, std::size_t count,
                               const std::string& option) {
    std::vector<double> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        try {
            std::size_t used = 0;
            const double v = std::stod(item, &used);
            if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
            values.push_back(v);
        } catch (const std::exception&) {
            throw std::invalid_argument(option + " '" + text + "': '" + item + "' is not a number");
        }
    }
    if (values.size() != count)
        throw std::invalid_argument(option + " '" + text + "' needs " + std::to_string(count) +
                                    " comma-separated values");
    return values;
}

// The planes of a CT (--like a series) along `frame`'s normal.
std::vector<double> planesOfSeries(const RtStructWriteOptions& like, const PlaneFrame& frame) {
    std::vector<double> zs;
    if (!like.imageSeries) return zs;
    for (const DicomImage& image : like.imageSeries->images)
        zs.push_back(dot(image.positionMm, frame.n));
    return zs;
}

void runAlgebra(const AlgebraArgs& args, const GlobalOptions& global, bool margin) {
    const bool toDicom = endsWithIgnoringCase(args.output, ".dcm");
    if (!toDicom && !endsWithIgnoringCase(args.output, ".slices"))
        throw std::invalid_argument("output '" + args.output + "' needs .slices or .dcm");
    if (!args.mesh.empty() && !isMeshOutputPath(args.mesh))
        throw std::invalid_argument("--mesh '" + args.mesh + "' needs a mesh extension (" +
                                    "ply, stl, obj, off, vtk, vtp)");
    if (!(args.stepMm >= 0.01 && args.stepMm <= 5))
        throw std::invalid_argument("--step must be within 0.01 .. 5 mm");
    if (!(args.meshVoxelMm >= 0.05 && args.meshVoxelMm <= 5))
        throw std::invalid_argument("--mesh-voxel must be within 0.05 .. 5 mm");
    // A name every format can hold, refused here rather than at the write.
    auto checkName = [](const std::string& name, const std::string& where) {
        const std::string problem = roiNameProblem(name);
        if (!problem.empty())
            throw std::invalid_argument(where + ": the new ROI's name " + problem +
                                        " (ROI names are UTF-8 text of at most " +
                                        std::to_string(kMaxRoiNameBytes) +
                                        " bytes, no control characters)");
    };
    if (!args.name.empty()) checkName(args.name, "--name");
    if (!margin && !roiExpressionName(args.expression).empty())
        checkName(roiExpressionName(args.expression), "--expr");
    const ContourInput input = loadContours(args.input, global, onlyRoi(args.roi));

    StructureAlgebraOptions options;
    options.sections.stepMm = args.stepMm;
    options.sections.minContourAreaMm2 = args.minAreaMm2;
    if (!args.mesh.empty()) options.surfaceVoxelMm = args.meshVoxelMm;
    options.backend = args.reference ? DistanceBackend::Reference : DistanceBackend::Device;
    if (!args.colour.empty()) {
        const std::vector<double> c = numberList(args.colour, 3, "--colour");
        for (double v : c)
            if (v < 0 || v > 255 || v != std::floor(v))
                throw std::invalid_argument("--colour '" + args.colour +
                                            "': each value is an integer 0..255");
        options.colour = Rgb{std::uint8_t(c[0]), std::uint8_t(c[1]), std::uint8_t(c[2])};
    }
    RtStructWriteOptions writeOptions;
    if (!args.like.empty())
        writeOptions = referenceFrom(args.like);
    else if (input.format == ContourFormat::RtStruct && toDicom)
        writeOptions = referenceFrom(args.input);

    ocl::Runtime runtime(global.device);
    // The sections are exact at any lattice; where the ones of one lattice
    // do not reconstruct (reconstruction still folds on some pairs of
    // planes whose sections nearly coincide), the next lattice is tried.
    StructureAlgebraResult result;
    RtStructWriteSummary summary;
    std::optional<ContourInput> back;
    std::optional<RoiSurface> rebuiltOnce;
    int attempts = 0;
    for (double shift : kLatticeShifts) {
        ++attempts;
        options.sections.latticeShift = shift;
        {
            // A lattice tried again starts the bar again, named so.
            Progress progress(
                std::string(margin ? "margin" : "combine") +
                    (attempts > 1 ? " (lattice " + std::to_string(attempts) + ")" : ""),
                !global.quiet);
            progress.update(0);
            options.progress = [&progress](double fraction) { progress.update(fraction); };
            RoiExpression expression;
            if (margin) {
                const Roi& source = *selectRois(input.contours, args.roi, false).front();
                DirectionalMargin m;
                if (!args.perDirection.empty()) {
                    const std::vector<double> v =
                        numberList(args.perDirection, 6, "--mm-per-direction");
                    std::copy(v.begin(), v.end(), m.mm.begin());
                } else {
                    m = DirectionalMargin::uniform(args.mm);
                }
                for (double v : m.mm)
                    if (std::abs(v) > 200)
                        throw std::invalid_argument("margins are limited to ±200 mm");
                options.interpretedType =
                    args.roiType.empty() ? source.interpretedType : args.roiType;
                const std::string name =
                    args.name.empty() ? marginRoiName(source.name, m) : args.name;
                if (args.name.empty()) checkName(name, "--roi '" + source.name + "' + margin");
                const PlaneFrame frame = source.frame;
                if (writeOptions.imageSeries)
                    options.planesMm = planesOfSeries(writeOptions, frame);
                result = marginRoi(runtime, input.contours, source.name, m, name, options);
            } else {
                std::vector<std::string> names;
                for (const Roi& roi : input.contours.rois) names.push_back(roi.name);
                expression = parseRoiExpression(args.expression, names);
                options.interpretedType = args.roiType.empty() ? "CONTROL" : args.roiType;
                if (writeOptions.imageSeries)
                    options.planesMm = planesOfSeries(
                        writeOptions, input.contours.findRoi(expression.rois().front())->frame);
                result = evaluateRoiExpression(runtime, input.contours, expression, options);
            }
            options.progress = nullptr;  // the bar ends here
        }
        Roi& made = result.roi;

        // The set written: every ROI read (unless --only-new) and the new one.
        ContourSet written;
        int nextNumber = 1;
        if (!args.onlyNew)
            for (const Roi& roi : input.contours.rois) {
                if (roi.defect)
                    throw InputError(args.input, roi.defect->line(),
                                     "ROI '" + roi.name + "' could not be read (" +
                                         roi.defect->problem() +
                                         "), so the structure set cannot be written whole; "
                                         "--only-new writes the new ROI alone");
                if (roi.name == made.name) {
                    if (!args.replace)
                        throw std::invalid_argument("the structure set already has an ROI named '" +
                                                    made.name +
                                                    "'; --name gives another, --replace "
                                                    "replaces it");
                    continue;
                }
                written.rois.push_back(roi);
                // The writer numbers an ROI without one by its position.
                nextNumber =
                    std::max(nextNumber, roi.number.value_or(int(written.rois.size())) + 1);
            }
        if (toDicom) made.number = nextNumber;
        written.rois.push_back(made);
        if (!toDicom)
            for (const Roi& roi : written.rois)
                if (!roi.frame.isIdentity())
                    throw std::invalid_argument(
                        "ROI '" + roi.name + "' lies in " + roi.frame.orientationName() +
                        " planes, and a .slices file holds axial planes only; "
                        "write a DICOM RTSTRUCT (.dcm)");

        if (toDicom) {
            writeOptions.structureSetLabel = "dfrecon";
            summary = writeRtStruct(written, args.output, writeOptions);
        } else {
            writeSlicesFile(written, args.output);
        }
        // The new ROI as written, read back and reconstructed as `reconstruct`
        // would (the file's rounding and the reader's checks included): what a
        // user gets from the file must be a valid closed solid.
        GlobalOptions quietly = global;
        quietly.quiet = true;
        back = loadContours(args.output, quietly);
        const Roi* read = back->contours.findRoi(made.name);
        if (!read)
            throw std::runtime_error(args.output + ": the new ROI '" + made.name +
                                     "' did not read back");
        rebuiltOnce = reconstructRoi(runtime, *read);
        if (rebuiltOnce->check.validSolid()) break;
    }
    Roi& made = result.roi;
    const RoiSurface& rebuilt = *rebuiltOnce;
    bool invalid = !rebuilt.check.validSolid();

    // The mesh: the exact surface of the result where the field allows it,
    // else the reconstruction of its contours.
    nlohmann::ordered_json meshReport;
    if (!args.mesh.empty()) {
        // OpenVDB's mesher can fold where two sheets of the surface pass
        // within a voxel; the reconstruction of the contours is then the mesh.
        std::optional<TriangleSoup> exact = result.surface;
        MeshCheckReport exactCheck;
        if (exact) {
            roundPointsToFloat(*exact);
            exactCheck = checkMesh(*exact);
        }
        const bool useExact = exact && exactCheck.validSolid();
        const TriangleSoup& surface = useExact ? *exact : rebuilt.surface;
        const MeshCheckReport& check = useExact ? exactCheck : rebuilt.check;
        const bool valid = check.validSolid();
        if (valid) {
            MeshWriteOptions write;
            write.structure = structureTagOf(made);
            writeMeshOutput(toTriMesh(surface), meshOutput(args.mesh, "", true), write);
        }
        invalid = invalid || !valid;
        meshReport = {{"path", args.mesh},
                      {"source", useExact ? "exact surface" : "contours reconstructed"},
                      {"exactSurface",
                       exact ? nlohmann::ordered_json{{"validSolid", exactCheck.validSolid()},
                                                      {"voxelMm", result.surfaceStats.voxelMm},
                                                      {"verticesOnExactBoundary",
                                                       result.surfaceStats.projected},
                                                      {"seconds", result.surfaceSeconds}}
                             : nlohmann::ordered_json()},
                      {"written", valid}};
        appendItems(meshReport, meshCheckJson(check));
    }
    const double contourCc = contourVolumeMm3(made) / kCubicMmPerCc;
    if (args.json) {
        nlohmann::ordered_json sources = nlohmann::ordered_json::object();
        for (const auto& [name, mm3] : result.surfaceVolumesMm3)
            sources[name] = mm3 / kCubicMmPerCc;
        nlohmann::ordered_json report{
            {"command", margin ? "margin" : "combine"},
            {"input", args.input},
            {"output", args.output},
            {"roi", made.name},
            {"expression", result.expression.text()},
            {"solid", "reconstructed surface"},
            {"stepMm", args.stepMm},
            {"planes", result.planesMm.size()},
            {"planesWithContours", made.slices.size()},
            {"contours", made.contourCount()},
            {"points", made.pointCount()},
            {"contourVolumeCc", contourCc},
            {"sourceSurfaceVolumesCc", sources},
            {"distanceQueries", result.sections.coarseSamples + result.sections.fineSamples +
                                    result.sections.refinementSamples},
            {"distanceQueriesByStage",
             {{"coarseLattice", result.sections.coarseSamples},
              {"nearBoundary", result.sections.fineSamples},
              {"verticesOntoBoundary", result.sections.refinementSamples}}},
            {"surfacesSeconds", result.surfacesSeconds},
            {"sectionsSeconds", result.sectionsSeconds}};
        report["contoursReconstructed"] = {{"validSolid", rebuilt.check.validSolid()},
                                           {"volumeCc", rebuilt.check.volumeMm3 / kCubicMmPerCc},
                                           {"latticesTried", attempts}};
        if (!args.mesh.empty()) report["mesh"] = meshReport;
        report["warnings"] = summary.warnings;
        std::cout << jsonText(report, 2) << "\n";
    } else {
        std::cout << made.name << " = " << result.expression.text() << ": " << made.slices.size()
                  << " planes, " << made.contourCount() << " contours, " << contourCc
                  << " cc (Σ area × spacing) -> " << args.output << "\n";
        std::cout << "  its contours reconstruct to " << rebuilt.check.volumeMm3 / kCubicMmPerCc
                  << " cc, "
                  << (rebuilt.check.validSolid() ? "a valid closed solid"
                                                 : "NOT a valid closed solid")
                  << "\n";
        if (!args.mesh.empty())
            std::cout << "  " << meshReport["source"].get<std::string>() << ": "
                      << meshReport["volumeCc"].get<double>() << " cc, "
                      << (meshReport["written"].get<bool>()
                              ? "valid -> " + args.mesh
                              : std::string("NOT a valid closed solid, not written"))
                      << "\n";
    }
    if (invalid)
        throw InvalidResult(
            "the new ROI '" + made.name + "' is not a valid closed solid (" +
            (rebuilt.check.validSolid() ? "its mesh" : "its contours reconstructed") + ")");
}

void addOutputOptions(CLI::App* cmd, AlgebraArgs& args) {
    cmd->add_option("file", args.input, contourInputHelp())->required();
    cmd->add_option("-o,--output", args.output,
                    "Output structure set: .dcm (RTSTRUCT) or .slices; holds every ROI read and "
                    "the new one")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--mesh", args.mesh,
                    "Also write the new ROI's exact surface in space (between the planes too) to "
                    "this mesh file (.ply .stl .obj .off .vtk .vtp); exit 4 if it is not a valid "
                    "closed solid")
        ->check(kNotStandardStream);
    cmd->add_option("--mesh-voxel", args.meshVoxelMm,
                    "Voxel (mm) on which the exact surface is found; its vertices are then moved "
                    "onto the exact boundary")
        ->capture_default_str();
    cmd->add_option("--name", args.name, "Name of the new ROI (margin; default ROI+MM or ROI-MM)");
    cmd->add_option("--like", args.like,
                    "A CT (folder or one image): the output refers to it, and the new ROI's "
                    "planes are its image planes (default: the ROIs' planes, continued at their "
                    "spacing where the result reaches beyond them)");
    cmd->add_option("--step", args.stepMm,
                    "Lattice step (mm) along which contour vertices are found on the exact "
                    "boundary; between vertices contours are chords")
        ->capture_default_str();
    cmd->add_option("--min-area", args.minAreaMm2,
                    "Drop islands and holes of the new ROI smaller than this (mm²) on each plane")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e6));
    cmd->add_option("--colour", args.colour, "Display colour of the new ROI, R,G,B in 0..255");
    std::vector<std::string> roiTypes(kRoiInterpretedTypes.begin(), kRoiInterpretedTypes.end());
    cmd->add_option("--roi-type", args.roiType,
                    "RT ROI Interpreted Type of the new ROI (margin: the source's; combine: "
                    "CONTROL)")
        ->check(CLI::IsMember(roiTypes));
    cmd->add_flag("--only-new", args.onlyNew, "Write the new ROI alone, not the whole set");
    cmd->add_flag("--replace", args.replace, "Replace an ROI of the same name");
    cmd->add_flag("--reference", args.reference,
                  "Compute distances with the C++ reference instead of the OpenCL kernel (slower; "
                  "for checking)");
    cmd->add_flag("--json", args.json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    asOutput(cmd->get_option("--mesh"), OutputKind::File);
}

const char* kAlgebraFooter =
    "The solid of each ROI is its reconstructed surface (reconstruct's defaults: it passes "
    "through every contour). A margin of M mm holds every point within M mm of that solid "
    "(the Minkowski sum with a ball, or with eight ellipsoid octants for per-direction values); a "
    "negative "
    "margin every point at least |M| mm inside it. Distances are exact (the closest triangle, "
    "signed by pseudo-normals); on each plane every contour vertex lies on the exact boundary "
    "within 1e-4 mm (or 5 % of --step off a lattice sample it passes near), and between "
    "vertices (--step apart) contours are chords. Planes: the "
    "ROIs' own, continued at their spacing as far as a growth reaches, or --like's images. "
    "Exit codes: 0 done, 1 usage (also an expression that does not parse), 2 bad input, "
    "3 runtime failure, 4 the new ROI (read back and reconstructed, or its --mesh) is not a valid "
    "closed solid.";

}  // namespace

void addMarginCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<AlgebraArgs>();
    CLI::App* cmd = root.add_subcommand("margin", "Grow or shrink an ROI by an exact 3D margin");
    cmd->footer(std::string(kAlgebraFooter) +
                " Example: dfrecon margin plan.dcm --roi CTV --mm 5 --name PTV -o plan+ptv.dcm");
    addOutputOptions(cmd, *args);
    cmd->add_option("--roi", args->roi, "The ROI to grow or shrink (name or DICOM number)")
        ->required();
    CLI::Option* mm =
        cmd->add_option("--mm", args->mm, "Margin in mm: > 0 grows, < 0 shrinks (at most 200)");
    CLI::Option* per = cmd->add_option(
        "--mm-per-direction", args->perDirection,
        "Margins R,L,A,P,S,I in mm (patient right, left, anterior, posterior, superior, "
        "inferior), all ≥ 0 or all ≤ 0: the body of eight ellipsoid octants with those "
        "semi-axes (an ellipsoid when R = L, A = P and S = I)");
    mm->excludes(per);
    cmd->callback([args, &global, mm, per] {
        if (mm->count() == 0 && per->count() == 0)
            throw CLI::ValidationError("margin", "give --mm or --mm-per-direction");
        runAlgebra(*args, global, true);
    });
}

void addCombineCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<AlgebraArgs>();
    CLI::App* cmd = root.add_subcommand(
        "combine",
        "A new ROI from an expression of ROIs and margins (union, intersection, "
        "difference, exclusive or)");
    cmd->footer(
        std::string(kAlgebraFooter) +
        " Expressions: NAME = EXPR; A | B or A + B union, A & B intersection, A - B "
        "difference, A ^ B exclusive or; A + 5 and A - 3 margins (mm) of the operand before "
        "them, A + [R,L,A,P,S,I] per direction; parentheses group. ROI names are matched "
        "longest first (PTV-70 is the ROI when there is one); quote others ('Lung L'). A "
        "margin of a union (growing) or of an intersection (shrinking) is exact; of anything "
        "else it is refused: make that ROI first, then grow it. Examples: \"Ring = (PTV + 20) "
        "- (PTV + 3)\", \"PTV_eval = PTV - Rectum\", \"Parotids = Parotid_L | Parotid_R\".");
    addOutputOptions(cmd, *args);
    cmd->add_option("--expr", args->expression, "The definition, NAME = EXPR")->required();
    cmd->callback([args, &global] { runAlgebra(*args, global, false); });
}

}  // namespace dfrecon::app
