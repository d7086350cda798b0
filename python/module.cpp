// The Python module dfrecon._dfrecon: the public C++ API (include/dfrecon/)
// with NumPy arrays in and out, and the command line's reports as dicts, so
// that a number means the same from Python as from `dfrecon ... --json`.
// dfrecon/__init__.py wraps it into the documented Python API
// (docs/python.md); names with a leading underscore are that file's.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include "cl/ClError.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "dfrecon/Segment.hpp"
#include "dfrecon/dfrecon.hpp"
#include "field/Rasterization.hpp"
#include "geometry/OrderedParallel.hpp"
#include "io/contours/ContourFormat.hpp"
#include "io/contours/RoiName.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/CompareReport.hpp"
#include "report/ExitCodes.hpp"
#include "report/ReconstructSettings.hpp"
#include "report/Reports.hpp"
#include "report/RoiMatching.hpp"
#include "report/RoiReport.hpp"
#include "report/SimplifyReport.hpp"
#include "segment/GeodesicDistances.hpp"
#include "segment/SpeedFunctions.hpp"

namespace py = pybind11;
using namespace dfrecon;

namespace {

// ---- the one OpenCL runtime of the process ----------------------------------

// Made on first use from $DFRECON_DEVICE (as the program does without
// --device), or from set_device(); one at a time, since kernels share its queue.
std::mutex runtimeMutex;
std::unique_ptr<ocl::Runtime> sharedRuntime;
std::string deviceSpec;

ocl::Runtime& runtime() {
    if (!sharedRuntime) sharedRuntime = std::make_unique<ocl::Runtime>(deviceSpec);
    return *sharedRuntime;
}

// Runs `work(runtime)` without the GIL, so that other Python threads go on
// while the device works, and with the runtime to itself.
template <class Work>
auto onDevice(Work&& work) {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(runtimeMutex);
    return work(runtime());
}

// ---- JSON to Python ---------------------------------------------------------

py::object toPython(const nlohmann::ordered_json& j) {
    switch (j.type()) {
        case nlohmann::ordered_json::value_t::null:
            return py::none();
        case nlohmann::ordered_json::value_t::boolean:
            return py::bool_(j.get<bool>());
        case nlohmann::ordered_json::value_t::number_integer:
            return py::int_(j.get<std::int64_t>());
        case nlohmann::ordered_json::value_t::number_unsigned:
            return py::int_(j.get<std::uint64_t>());
        case nlohmann::ordered_json::value_t::number_float:
            return py::float_(j.get<double>());
        case nlohmann::ordered_json::value_t::string:
            return py::str(j.get<std::string>());
        case nlohmann::ordered_json::value_t::array: {
            py::list list;
            for (const auto& item : j) list.append(toPython(item));
            return std::move(list);
        }
        case nlohmann::ordered_json::value_t::object: {
            py::dict dict;
            for (const auto& [key, value] : j.items()) dict[py::str(key)] = toPython(value);
            return std::move(dict);
        }
        default:
            return py::none();
    }
}

// ---- arrays -----------------------------------------------------------------

// Points (n, 3) float64 from any array-like, refusing what is not one
// (wrong shape, non-numbers) with a message naming `what`.
// An array of the kinds NumPy calls numbers and dfrecon takes as
// coordinates or indices: integers and reals (not booleans, complex
// numbers, strings or objects, which a cast would turn into numbers
// silently). Anything that is not such an array is refused, naming `what`.
py::array numericArray(const py::handle& object, const std::string& what, const char* kinds) {
    py::array a;
    try {
        a = py::array::ensure(object);
    } catch (const py::error_already_set&) {
        a = py::array();
    }
    if (!a) throw py::value_error(what + ": not an array of numbers");
    const char kind = a.dtype().kind();
    if (std::string(kinds).find(kind) == std::string::npos)
        throw py::value_error(what + ": expected " +
                              (std::string(kinds) == "iu" ? "integers" : "numbers") +
                              ", got dtype " + std::string(py::str(a.dtype())));
    return a;
}

std::string shapeText(const py::array& a) {
    std::string text = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
    return text + (a.ndim() == 1 ? ",)" : ")");
}

// Most rows of a vertex or face array: indices are 32-bit and read as
// int32 by the views (below 2^31), and each row is made in C++ memory.
constexpr py::ssize_t kMaxRows = (py::ssize_t(1) << 31) - 1;

// `given` as a C-ordered array of T, converted (a copy) where it is not one
// already: sizes checked before the copy, which numpy makes in full even for
// a broadcast view of one row, and the copy checked (pybind11's ensure()
// returns nothing, not an exception, when numpy cannot make it).
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> rowsOf(const py::array& given,
                                                                 const std::string& what) {
    if (given.shape(0) > kMaxRows)
        throw py::value_error(what + ": " + std::to_string(given.shape(0)) +
                              " rows, more than the 2^31 - 1 a mesh may have");
    auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(given);
    if (!a) throw std::bad_alloc();  // MemoryError in Python
    return a;
}

// Points (n, 3) as float64 from any array of integers or reals.
std::vector<Vec3> pointsOf(const py::handle& object, const std::string& what) {
    const py::array given = numericArray(object, what, "iuf");
    if (given.ndim() != 2 || given.shape(1) != 3)
        throw py::value_error(what + ": expected an array of shape (n, 3), got shape " +
                              shapeText(given));
    const auto a = rowsOf<double>(given, what);
    std::vector<Vec3> points(std::size_t(a.shape(0)));
    const double* data = a.data();
    for (std::size_t i = 0; i < points.size(); ++i)
        points[i] = {data[3 * i], data[3 * i + 1], data[3 * i + 2]};
    return points;
}

py::array_t<double> pointsArray(const std::vector<Vec3>& points) {
    py::array_t<double> a({py::ssize_t(points.size()), py::ssize_t(3)});
    double* out = a.mutable_data();
    for (std::size_t i = 0; i < points.size(); ++i) {
        out[3 * i] = points[i].x;
        out[3 * i + 1] = points[i].y;
        out[3 * i + 2] = points[i].z;
    }
    return a;
}

// Rows of three values at `data` as an (n, 3) array that views them (no
// copy), kept alive by `owner`, read-only.
template <class T>
py::array_t<T> readOnlyView(const T* data, std::size_t rows, const py::object& owner) {
    py::array_t<T> view({py::ssize_t(rows), py::ssize_t(3)},
                        {py::ssize_t(3 * sizeof(T)), py::ssize_t(sizeof(T))}, data, owner);
    py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
}
// The views rely on these layouts: a point is three doubles, a triangle
// three 32-bit indices (below 2^31, as int32 reads them: more vertices
// would take 48 GB for their points alone).
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is three packed doubles");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::int32_t),
              "a triangle is three packed indices");

// A surface from vertex and face arrays: faces must be integers (any width)
// indexing the vertices, vertices finite.
TriangleSoup soupOf(const py::handle& vertices, const py::handle& faces) {
    TriangleSoup soup;
    soup.points = pointsOf(vertices, "vertices");
    for (std::size_t i = 0; i < soup.points.size(); ++i) {
        const Vec3& p = soup.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw py::value_error("vertices: vertex " + std::to_string(i) +
                                  " has a coordinate that is not a finite number");
    }
    const py::array f = numericArray(faces, "faces", "iu");
    if (f.ndim() != 2 || f.shape(1) != 3)
        throw py::value_error("faces: expected an integer array of shape (m, 3), got shape " +
                              shapeText(f));
    const auto indices = rowsOf<std::int64_t>(f, "faces");
    const std::int64_t* data = indices.data();
    soup.triangles.resize(std::size_t(f.shape(0)));
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::int64_t v = data[3 * t + k];
            if (v < 0 || std::uint64_t(v) >= soup.points.size())
                throw py::value_error("faces: face " + std::to_string(t) + " refers to vertex " +
                                      std::to_string(v) + ", but there are " +
                                      std::to_string(soup.points.size()) + " vertices");
            soup.triangles[t][k] = std::uint32_t(v);
        }
    return soup;
}

// ---- structure sets ---------------------------------------------------------

py::dict roiDict(const Roi& roi, const std::vector<InputWarning>& warnings = {}) {
    py::dict d;
    d["name"] = roi.name;
    // The reading's warnings about this ROI (InputWarning::roi).
    py::list own;
    for (const InputWarning& w : warnings)
        if (w.roi == roi.name) own.append(w.toString());
    d["warnings"] = own;
    d["number"] = roi.number ? py::object(py::int_(*roi.number)) : py::none();
    d["colour"] = roi.colour
                      ? py::object(py::make_tuple(int((*roi.colour)[0]), int((*roi.colour)[1]),
                                                  int((*roi.colour)[2])))
                      : py::none();
    // None where the file gives none, as --json's null.
    d["interpreted_type"] = roi.interpretedType.empty() ? py::object(py::none())
                                                        : py::object(py::str(roi.interpretedType));
    d["defect"] = roi.defect ? py::object(py::str(roi.defect->what())) : py::none();
    py::array_t<double> planes(py::ssize_t(roi.slices.size()));
    py::list contours;
    for (std::size_t k = 0; k < roi.slices.size(); ++k) {
        const Slice& slice = roi.slices[k];
        // Plane positions along the stack's normal; points in patient mm.
        planes.mutable_data()[k] = slice.zMm;
        for (const Polygon& polygon : slice.contours) {
            std::vector<Vec3> points;
            points.reserve(polygon.size());
            for (Point2 p : polygon) points.push_back(roi.frame.toPatient({p.x, p.y, slice.zMm}));
            contours.append(pointsArray(points));
        }
    }
    d["planes"] = planes;
    d["contours"] = contours;
    d["contour_volume_cc"] = roi.slices.empty() ? 0.0 : contourVolumeMm3(roi) / 1000;
    d["orientation"] = roi.frame.orientationName();
    const PlaneReadingCounts& r = roi.reading;
    py::dict reading;
    reading["rule"] = "even-odd";
    reading["repeated_points"] = r.repeatedPoints;
    reading["fold_points"] = r.foldPoints;
    reading["zero_area_contours"] = r.zeroAreaContours;
    reading["duplicate_contours"] = r.duplicateContours;
    reading["keyhole_cuts"] = r.keyholeCuts;
    reading["resolved_contours"] = r.resolvedContours;
    reading["planes_resolved"] = r.planesResolved;
    reading["changed_shape"] = r.changedShape();
    d["contour_reading"] = reading;
    return d;
}

// The structure set as Python sees it: the C++ object kept opaque (for
// reconstruct and the fields), its ROIs described by roiDict.
struct PyStructureSet {
    ContoursRead read;
    std::string source;
};

PyStructureSet readSet(const std::string& path, const std::string& labelTable,
                       bool acceptIntensity) {
    ReadContoursOptions options;
    options.labelTable = labelTable;
    options.acceptIntensity = acceptIntensity;
    PyStructureSet set;
    {
        py::gil_scoped_release release;
        set.read = readContours(path, options);
    }
    set.source = path;
    return set;
}

PyStructureSet setFromContours(const py::dict& rois, const py::dict& colours) {
    std::vector<RoiPoints> points;
    for (const auto& [key, value] : rois) {
        RoiPoints roi;
        if (!py::isinstance<py::str>(key))
            throw py::type_error("from_contours: ROI names must be str, got " +
                                 std::string(py::str(py::type::of(key))));
        roi.name = py::cast<std::string>(key);
        if (py::isinstance<py::array>(value) || !py::isinstance<py::sequence>(value))
            throw py::type_error("from_contours: ROI '" + roi.name +
                                 "': expected a list of (n, 3) arrays, one per contour");
        std::size_t index = 0;
        for (const py::handle& contour : value)
            roi.contours.push_back(pointsOf(contour, "from_contours: ROI '" + roi.name +
                                                         "', contour " + std::to_string(index++)));
        if (colours.contains(key)) {
            const auto c = py::cast<std::vector<int>>(colours[key]);
            if (c.size() != 3 ||
                std::any_of(c.begin(), c.end(), [](int v) { return v < 0 || v > 255; }))
                throw py::value_error("from_contours: colour of ROI '" + roi.name +
                                      "' must be three integers 0-255");
            roi.colour = Rgb{std::uint8_t(c[0]), std::uint8_t(c[1]), std::uint8_t(c[2])};
        }
        points.push_back(std::move(roi));
    }
    ReadContoursOptions options;
    PyStructureSet set;
    set.read = structureSetFromPoints(points, "StructureSet.from_contours", options);
    set.source = "StructureSet.from_contours";
    return set;
}

// ---- reconstruct ------------------------------------------------------------

struct PyMesh {
    TriangleSoup surface;
    std::string name;
    std::optional<Rgb> colour;
    double contourVolumeMm3 = NAN;
    py::object report = py::none();
};

const Roi& chooseRoi(const ContoursRead& read, const py::object& roi) {
    const ContourSet& set = read.contours;
    const Roi* chosen = nullptr;
    if (roi.is_none()) {
        if (set.rois.size() != 1)
            throw py::value_error("the structure set holds " + std::to_string(set.rois.size()) +
                                  " ROIs: name one (roi=...)");
        chosen = &set.rois.front();
    } else if (py::isinstance<py::int_>(roi)) {
        chosen = set.findRoiNumber(py::cast<int>(roi));
        if (!chosen) throw py::key_error("no ROI numbered " + std::string(py::str(roi)));
    } else {
        const std::string name = py::cast<std::string>(roi);
        chosen = set.findRoi(name);
        if (!chosen) throw py::key_error("no ROI named '" + name + "'");
    }
    if (chosen->defect) throw *chosen->defect;
    if (chosen->slices.empty())
        throw py::value_error("ROI '" + chosen->name + "' has no closed planar contours");
    return *chosen;
}

ReconstructSettings settingsOf(const std::vector<std::pair<std::string, std::string>>& given) {
    std::vector<GivenOption> options;
    for (const auto& [name, value] : given) options.push_back({name, value, "reconstruct()"});
    return withGivenOptions({}, options);
}

// The mesh Python gets for `result` of `roi`, with reconstruct --json's
// per-ROI report.
PyMesh meshOf(const PyStructureSet& set, const Roi& roi, RoiSurface result,
              const ReconstructSettings& settings) {
    const nlohmann::ordered_json simplification =
        result.simplification
            ? simplificationJson(*result.simplification, SimplifyOptions{settings.maxErrorMm}, true)
            : nlohmann::ordered_json(nullptr);
    nlohmann::ordered_json report =
        roiReport(roi, result, set.read.dicomInfo(roi), settings, {}, simplification);
    // Nothing is written from Python: the file keys would only mislead.
    report.erase("output");
    report.erase("written");
    report.erase("facesRefusedByOpenMesh");
    PyMesh mesh;
    mesh.surface = std::move(result.surface);
    mesh.name = roi.name;
    mesh.colour = roi.colour;
    mesh.contourVolumeMm3 = result.contourVolumeMm3;
    mesh.report = toPython(report);
    return mesh;
}

PyMesh reconstructOne(const PyStructureSet& set, const py::object& roiChoice,
                      const std::vector<std::pair<std::string, std::string>>& given) {
    const Roi& roi = chooseRoi(set.read, roiChoice);
    const ReconstructSettings settings = settingsOf(given);
    RoiSurface result = onDevice([&](ocl::Runtime& device) {
        return reconstructRoi(device, roi,
                              RoiReconstructOptions{settings.options, settings.maxErrorMm});
    });
    return meshOf(set, roi, std::move(result), settings);
}

// Several ROIs at once, as `reconstruct --all --jobs` runs them: `jobs`
// workers (0: one per core), each with its own OpenCL queue, results in the
// given order. The first ROI that fails raises its error. With `apart`,
// the neighbours are moved apart before any is simplified, as `reconstruct
// --all --neighbours apart` does.
std::vector<PyMesh> reconstructMany(const PyStructureSet& set,
                                    const std::vector<std::string>& names,
                                    const std::vector<std::pair<std::string, std::string>>& given,
                                    unsigned jobs, bool apart) {
    std::vector<const Roi*> rois;
    for (const std::string& name : names) rois.push_back(&chooseRoi(set.read, py::str(name)));
    const ReconstructSettings settings = settingsOf(given);
    const std::size_t workers =
        jobs > 0 ? std::min<std::size_t>(jobs, rois.size()) : defaultJobs(rois.size());
    std::vector<RoiSurface> results(rois.size());
    {
        py::gil_scoped_release release;
        ocl::WorkerRuntimes runtimes(deviceSpec, workers);
        forEachInOrder(
            rois.size(), workers,
            [&](std::size_t i, std::size_t worker) {
                return reconstructRoi(
                    runtimes[worker], *rois[i],
                    RoiReconstructOptions{settings.options, apart ? 0 : settings.maxErrorMm});
            },
            [&](std::size_t i, RoiSurface result) { results[i] = std::move(result); });
        if (apart) {
            std::vector<RoiSurface*> surfaces;
            for (RoiSurface& result : results) surfaces.push_back(&result);
            keepNeighboursApart(runtimes[0], rois, surfaces);
            if (settings.maxErrorMm > 0)
                forEachInOrder(
                    rois.size(), workers,
                    [&](std::size_t i, std::size_t worker) {
                        simplifyRoiSurface(runtimes[worker], *rois[i], results[i],
                                           settings.maxErrorMm);
                        return 0;
                    },
                    [](std::size_t, int) {});
        }
    }
    std::vector<PyMesh> meshes;
    for (std::size_t i = 0; i < rois.size(); ++i)
        meshes.push_back(meshOf(set, *rois[i], std::move(results[i]), settings));
    return meshes;
}

// ---- meshes -----------------------------------------------------------------

nlohmann::ordered_json checkJson(const TriangleSoup& soup) {
    const MeshCheckReport check = checkMesh(soup);
    nlohmann::ordered_json report = meshCheckJson(check);
    appendItems(report, defectLocationsJson(check, soup));
    return report;
}

ComparedSolid solidOf(const PyMesh& mesh, const char* side) {
    ComparedSolid solid{mesh.surface, checkMesh(mesh.surface), nullptr};
    if (!solid.check.validSolid())
        throw py::value_error(std::string("compare: ") + side +
                              " is not a valid closed solid (dfrecon.check says where)");
    return solid;
}

}  // namespace

// ---- structure algebra -----------------------------------------------------

// What margin() and combine() take besides the expression, as the program's
// options of the same names: `settings` holds step_mm, min_area_mm2, colour
// (None or three integers) and roi_type ("" for the default, `defaultType`).
StructureAlgebraOptions algebraOptions(const py::dict& settings, const std::string& defaultType,
                                       const std::string& what) {
    const double stepMm = py::cast<double>(settings["step_mm"]);
    const double minAreaMm2 = py::cast<double>(settings["min_area_mm2"]);
    const py::object colour = settings["colour"];
    std::string roiType = py::cast<std::string>(settings["roi_type"]);
    if (roiType.empty()) roiType = defaultType;
    if (!(stepMm >= 0.01 && stepMm <= 5))
        throw py::value_error(what + ": step_mm must be within 0.01 .. 5 mm");
    if (!(minAreaMm2 >= 0 && minAreaMm2 <= 1e6))
        throw py::value_error(what + ": min_area_mm2 must be within 0 .. 1e6 mm²");
    StructureAlgebraOptions options;
    options.sections.stepMm = stepMm;
    options.sections.minContourAreaMm2 = minAreaMm2;
    if (!colour.is_none()) {
        const auto c = py::cast<std::vector<int>>(colour);
        if (c.size() != 3 ||
            std::any_of(c.begin(), c.end(), [](int v) { return v < 0 || v > 255; }))
            throw py::value_error(what + ": colour must be three integers 0-255");
        options.colour = Rgb{std::uint8_t(c[0]), std::uint8_t(c[1]), std::uint8_t(c[2])};
    }
    if (!roiType.empty() && !isRoiInterpretedType(roiType))
        throw py::value_error(what + ": roi_type '" + roiType +
                              "' is not an RT ROI Interpreted Type");
    options.interpretedType = roiType;
    return options;
}

// `evaluate(options)` on each lattice of kLatticeShifts in turn until the new
// ROI reconstructs into a valid closed solid, as the program's margin and
// combine do; the last one otherwise (its report says it is not valid).
template <class Evaluate>
std::pair<StructureAlgebraResult, RoiSurface> onLattices(StructureAlgebraOptions options,
                                                         Evaluate&& evaluate) {
    return onDevice([&](ocl::Runtime& device) {
        std::pair<StructureAlgebraResult, RoiSurface> made;
        for (const double shift : kLatticeShifts) {
            options.sections.latticeShift = shift;
            made.first = evaluate(device, options);
            made.second = reconstructRoi(device, made.first.roi, options.surfaces);
            if (made.second.check.validSolid()) break;
        }
        return made;
    });
}

// The set with the new ROI added last, numbered after every other, and a
// report of it as the program's --json gives one.
py::tuple withNewRoi(const PyStructureSet& set, std::pair<StructureAlgebraResult, RoiSurface> made,
                     const std::string& what) {
    Roi& roi = made.first.roi;
    const std::string problem = roiNameProblem(roi.name);
    if (!problem.empty()) throw py::value_error(what + ": the new ROI's name " + problem);
    if (set.read.contours.findRoi(roi.name))
        throw py::value_error(what + ": the structure set already has an ROI named '" + roi.name +
                              "' (name=... gives another)");
    PyStructureSet out = set;
    // After every number a written RTSTRUCT gives (an ROI without one is
    // numbered by its position).
    int next = 1;
    for (std::size_t k = 0; k < out.read.contours.rois.size(); ++k)
        next = std::max(next, out.read.contours.rois[k].number.value_or(int(k) + 1) + 1);
    roi.number = next;
    const MeshCheckReport& check = made.second.check;
    py::dict report;
    report["roi"] = roi.name;
    report["expression"] = made.first.expression.text();
    report["planes"] = roi.slices.size();
    report["contourVolumeCc"] = contourVolumeMm3(roi) / kCubicMmPerCc;
    report["surfaceVolumeCc"] = check.volumeMm3 / kCubicMmPerCc;
    report["validSolid"] = check.validSolid();
    py::dict sources;
    for (const auto& [name, mm3] : made.first.surfaceVolumesMm3)
        sources[py::str(name)] = mm3 / kCubicMmPerCc;
    report["sourceSurfaceVolumesCc"] = sources;
    out.read.contours.rois.push_back(std::move(roi));
    return py::make_tuple(std::move(out), report);
}

PYBIND11_MODULE(_dfrecon, m) {
    m.doc() = "dfrecon's C++ core; use the documented API of the dfrecon package";
    m.attr("__version__") = version();

    // Exceptions: bad input is a ValueError naming the file; a result that
    // is not one, and device failures, are RuntimeErrors.
    static py::exception<InputError> inputError(m, "InputError", PyExc_ValueError);
    static py::exception<InvalidResult> invalidResult(m, "InvalidResultError", PyExc_RuntimeError);
    static py::exception<ocl::ClError> deviceError(m, "DeviceError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            // The message as str(error), the file and line as attributes.
            py::object error = py::reinterpret_borrow<py::object>(inputError.ptr())(e.what());
            error.attr("file") = e.file();
            error.attr("line") = e.line();
            PyErr_SetObject(inputError.ptr(), error.ptr());
        } catch (const InvalidResult& e) {
            invalidResult(e.what());
        } catch (const ocl::ClError& e) {
            deviceError((std::string("OpenCL: ") + e.what()).c_str());
        } catch (const std::invalid_argument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "out of memory");
        }
    });

    m.def("_set_device", [](const std::string& spec) {
        const std::lock_guard<std::mutex> lock(runtimeMutex);
        auto next = std::make_unique<ocl::Runtime>(spec);
        sharedRuntime = std::move(next);
        deviceSpec = spec;
    });
    m.def("_device_name", [] {
        const std::lock_guard<std::mutex> lock(runtimeMutex);
        return runtime().device().deviceName;
    });

    py::class_<PyStructureSet>(m, "_StructureSet")
        .def_property_readonly(
            "format", [](const PyStructureSet& s) { return contourFormatName(s.read.format); })
        .def_property_readonly("source", [](const PyStructureSet& s) { return s.source; })
        .def_property_readonly("warnings",
                               [](const PyStructureSet& s) {
                                   std::vector<std::string> out;
                                   for (const InputWarning& w : s.read.warnings)
                                       out.push_back(w.toString());
                                   return out;
                               })
        .def("_rois",
             [](const PyStructureSet& s) {
                 py::list rois;
                 for (const Roi& roi : s.read.contours.rois)
                     rois.append(roiDict(roi, s.read.warnings));
                 return rois;
             })
        .def("_write_slices",
             [](const PyStructureSet& s, const std::string& path) {
                 writeSlicesFile(s.read.contours, path);
             })
        .def("_write_rtstruct",
             [](const PyStructureSet& s, const std::string& path, const std::string& like) {
                 // The references of `like` (a CT folder or an RTSTRUCT), else of
                 // the set's own source when it is an RTSTRUCT: a structure set
                 // that goes back to the planning system stays on its images.
                 RtStructWriteOptions options;
                 if (!like.empty())
                     options = referenceFrom(like);
                 else if (s.read.format == ContourFormat::RtStruct)
                     options = referenceFrom(s.source);
                 options.structureSetLabel = "dfrecon";
                 py::gil_scoped_release release;
                 writeRtStruct(s.read.contours, path, options);
             });

    m.def("_read_contours", &readSet, py::arg("path"), py::arg("label_table"),
          py::arg("accept_intensity"));
    m.def("_from_contours", &setFromContours, py::arg("rois"), py::arg("colours"));

    m.def("_margin",
          [](const PyStructureSet& set, const py::object& roiChoice, const std::vector<double>& mm,
             const std::string& name, const py::dict& settings) {
              const Roi& source = chooseRoi(set.read, roiChoice);
              if (mm.size() != 1 && mm.size() != 6)
                  throw py::value_error("margin(): mm is one number or six (R, L, A, P, S, I)");
              DirectionalMargin margin = DirectionalMargin::uniform(mm[0]);
              if (mm.size() == 6) std::copy(mm.begin(), mm.end(), margin.mm.begin());
              for (const double v : margin.mm)
                  if (!std::isfinite(v) || std::abs(v) > 200)
                      throw py::value_error("margin(): mm must be finite and within ±200 mm");
              if (margin.isZero() || (margin.grows() && margin.shrinks()))
                  throw py::value_error("margin(): mm must all grow (> 0) or all shrink (< 0)");
              const std::string newName = !name.empty() ? name : marginRoiName(source.name, margin);
              StructureAlgebraOptions options = algebraOptions(settings, "", "margin()");
              if (options.interpretedType.empty()) options.interpretedType = source.interpretedType;
              auto made =
                  onLattices(options, [&](ocl::Runtime& device, const StructureAlgebraOptions& o) {
                      return marginRoi(device, set.read.contours, source.name, margin, newName, o);
                  });
              return withNewRoi(set, std::move(made), "margin()");
          });

    m.def("_combine",
          [](const PyStructureSet& set, const std::string& definition, const py::dict& settings) {
              StructureAlgebraOptions options = algebraOptions(settings, "CONTROL", "combine()");
              std::vector<std::string> names;
              for (const Roi& roi : set.read.contours.rois) names.push_back(roi.name);
              RoiExpression expression;
              try {
                  expression = parseRoiExpression(definition, names);
              } catch (const ExpressionError& e) {
                  throw py::value_error(std::string("combine(): ") + e.what());
              }
              const std::string problem = roiNameProblem(expression.name);
              if (!problem.empty())
                  throw py::value_error("combine(): the new ROI's name " + problem);
              auto made =
                  onLattices(options, [&](ocl::Runtime& device, const StructureAlgebraOptions& o) {
                      return evaluateRoiExpression(device, set.read.contours, expression, o);
                  });
              return withNewRoi(set, std::move(made), "combine()");
          });

    m.def("_rasterize", [](const PyStructureSet& set, const py::object& roiChoice, double voxelMm,
                           const std::vector<std::pair<std::string, std::string>>& given) {
        const Roi& roi = chooseRoi(set.read, roiChoice);
        if (!(voxelMm >= 0.05 && voxelMm <= 50))
            throw py::value_error("rasterize(): voxel_mm must be within 0.05 .. 50 mm");
        const ReconstructSettings settings = settingsOf(given);
        const VolumeGeometry grid = gridAroundRois({&roi}, voxelMm);
        if (grid.voxelCount() > (std::size_t(1) << 31))
            throw py::value_error("rasterize(): " + std::to_string(grid.voxelCount()) +
                                  " voxels at voxel_mm=" + std::to_string(voxelMm) +
                                  " (more than 2^31): give a larger voxel_mm");
        std::vector<std::size_t> inside;
        double surfaceVolumeMm3 = 0;
        onDevice([&](ocl::Runtime& device) {
            const RoiSurface solid = reconstructRoi(
                device, roi, RoiReconstructOptions{settings.options, settings.maxErrorMm});
            surfaceVolumeMm3 = solid.check.volumeMm3;
            inside = roiSolidVoxelsInside(roi, solid, grid);
            return 0;
        });
        // (z, y, x): the array's axes are the grid's axes 2, 1, 0.
        py::array_t<bool> mask(
            {py::ssize_t(grid.size[2]), py::ssize_t(grid.size[1]), py::ssize_t(grid.size[0])});
        bool* out = mask.mutable_data();
        std::fill(out, out + grid.voxelCount(), false);
        for (const std::size_t v : inside) out[v] = true;
        py::dict result;
        result["values"] = mask;
        result["origin"] = py::make_tuple(grid.originMm[0], grid.originMm[1], grid.originMm[2]);
        result["spacing"] = py::make_tuple(grid.spacingMm[2], grid.spacingMm[1], grid.spacingMm[0]);
        py::list directions;
        for (int axis = 2; axis >= 0; --axis)
            directions.append(py::make_tuple(grid.direction[axis][0], grid.direction[axis][1],
                                             grid.direction[axis][2]));
        result["directions"] = directions;
        result["voxels"] = inside.size();
        result["volume_cc"] = double(inside.size()) * grid.spacingMm[0] * grid.spacingMm[1] *
                              grid.spacingMm[2] / kCubicMmPerCc;
        result["surface_volume_cc"] = surfaceVolumeMm3 / kCubicMmPerCc;
        return result;
    });

    m.def("_histogram",
          [](const PyStructureSet& set, const py::object& oarChoice, const py::object& targetChoice,
             double volumeStepMm, double surfaceSpacingMm) {
              const Roi& oar = chooseRoi(set.read, oarChoice);
              const Roi& target = chooseRoi(set.read, targetChoice);
              if (!(volumeStepMm > 0) || !std::isfinite(volumeStepMm) || !(surfaceSpacingMm > 0) ||
                  !std::isfinite(surfaceSpacingMm))
                  throw py::value_error(
                      "histogram(): volume_step_mm and surface_spacing_mm must be finite and > 0");
              DistanceHistogramOptions options;
              options.volumeStepMm = volumeStepMm;
              options.surfaceSpacingMm = surfaceSpacingMm;
              const DistanceHistograms h = onDevice([&](ocl::Runtime& device) {
                  return roiDistanceHistograms(device, set.read.contours, oar.name, target.name, {},
                                               options);
              });
              auto weighted = [](const WeightedDistances& w) {
                  py::dict d;
                  d["distance_mm"] =
                      py::array_t<double>(py::ssize_t(w.distanceMm.size()), w.distanceMm.data());
                  d["weight"] = py::array_t<double>(py::ssize_t(w.weight.size()), w.weight.data());
                  d["total"] = w.total;
                  return d;
              };
              py::dict out;
              out["volume"] = weighted(h.volume);
              out["surface"] = weighted(h.surface);
              out["volume_step_mm"] = h.volumeStepMm;
              out["surface_spacing_mm"] = h.surfaceSpacingMm;
              out["oar_volume_cc"] = h.oarVolumeMm3 / kCubicMmPerCc;
              out["oar_area_mm2"] = h.oarAreaMm2;
              return out;
          });

    py::class_<PyMesh>(m, "_Mesh")
        .def(py::init([](const py::object& vertices, const py::object& faces) {
            PyMesh made;
            made.surface = soupOf(vertices, faces);
            return made;
        }))
        // Views of the mesh's own arrays, not copies: read-only, since a
        // mesh's checks and reports describe the surface as it was made.
        .def_property_readonly("vertices",
                               [](py::object self) {
                                   const TriangleSoup& soup = self.cast<const PyMesh&>().surface;
                                   return readOnlyView<double>(
                                       reinterpret_cast<const double*>(soup.points.data()),
                                       soup.points.size(), self);
                               })
        .def_property_readonly("faces",
                               [](py::object self) {
                                   const TriangleSoup& soup = self.cast<const PyMesh&>().surface;
                                   return readOnlyView<std::int32_t>(
                                       reinterpret_cast<const std::int32_t*>(soup.triangles.data()),
                                       soup.triangles.size(), self);
                               })
        .def_property_readonly("name", [](const PyMesh& mesh) { return mesh.name; })
        .def_property_readonly("colour",
                               [](const PyMesh& mesh) -> py::object {
                                   if (!mesh.colour) return py::none();
                                   return py::make_tuple(int((*mesh.colour)[0]),
                                                         int((*mesh.colour)[1]),
                                                         int((*mesh.colour)[2]));
                               })
        .def_property_readonly("contour_volume_cc",
                               [](const PyMesh& mesh) -> py::object {
                                   if (std::isnan(mesh.contourVolumeMm3)) return py::none();
                                   return py::float_(mesh.contourVolumeMm3 / 1000);
                               })
        .def_property_readonly("report", [](const PyMesh& mesh) { return mesh.report; })
        .def("_check", [](const PyMesh& mesh) { return toPython(checkJson(mesh.surface)); })
        .def("_write", [](const PyMesh& mesh, const std::string& path, bool binary) {
            MeshWriteOptions options;
            options.binary = binary;
            if (!mesh.name.empty()) options.structure = StructureTag{mesh.name, mesh.colour};
            writeMesh(toTriMesh(mesh.surface), path, options);
        });
    // Whether a path names a mesh file dfrecon reads (io/mesh/MeshIO's one list).
    m.def("_is_mesh_path", &isMeshExtension);
    m.def("_read_mesh", [](const std::string& path) {
        PyMesh mesh;
        {
            py::gil_scoped_release release;
            mesh.surface = readTriangleSoup(path);
        }
        return mesh;
    });

    m.def("_reconstruct", &reconstructOne, py::arg("structure_set"), py::arg("roi"),
          py::arg("options"));
    m.def("_reconstruct_many", &reconstructMany, py::arg("structure_set"), py::arg("rois"),
          py::arg("options"), py::arg("jobs"), py::arg("apart"));
    m.def("_reconstruct_option_names", &reconstructSettingsNames);

    m.def("_simplify", [](const PyMesh& mesh, double maxErrorMm) {
        SimplifyOptions options;
        options.maxErrorMm = maxErrorMm;
        VerifiedSimplification simplified = onDevice(
            [&](ocl::Runtime& device) { return simplifyVerified(&device, mesh.surface, options); });
        PyMesh out;
        out.report = toPython(simplificationJson(simplified, options, false));
        out.surface = std::move(simplified.result.surface);
        out.name = mesh.name;
        out.colour = mesh.colour;
        return out;
    });

    m.def("_slice_fields", [](const PyStructureSet& set, const py::object& roiChoice,
                              double pixelMm) {
        const Roi& roi = chooseRoi(set.read, roiChoice);
        RoiFieldOptions options;
        options.pixelMm = pixelMm;
        const SliceFields fields =
            onDevice([&](ocl::Runtime& device) { return roiSliceFields(device, roi, options); });
        const SliceGrid& g = fields.grid;
        py::array_t<float> distance(
            {py::ssize_t(fields.sliceCount()), py::ssize_t(g.height), py::ssize_t(g.width)});
        std::copy(fields.distanceMm.begin(), fields.distanceMm.end(), distance.mutable_data());
        py::dict out;
        out["values"] = distance;
        out["planes"] = py::array_t<double>(py::ssize_t(fields.zMm.size()), fields.zMm.data());
        // Pixel (i, j) is centred half a pixel inside the grid's corner.
        out["origin"] = py::make_tuple(g.originMm.x + g.pixelMm / 2, g.originMm.y + g.pixelMm / 2);
        out["spacing"] = py::make_tuple(g.pixelMm, g.pixelMm);
        out["orientation"] = roi.frame.orientationName();
        return out;
    });

    m.def("_distance_field", [](const PyStructureSet& set, const py::object& roiChoice,
                                double pixelMm, bool isotropic) {
        const Roi& roi = chooseRoi(set.read, roiChoice);
        RoiFieldOptions options;
        options.pixelMm = pixelMm;
        options.isotropic = isotropic;
        const RoiDistanceVolume field =
            onDevice([&](ocl::Runtime& device) { return roiDistanceVolume(device, roi, options); });
        const DenseDistanceVolume& v = field.volume;
        py::array_t<float> values({py::ssize_t(v.nz), py::ssize_t(v.ny), py::ssize_t(v.nx)});
        std::copy(v.valuesMm.begin(), v.valuesMm.end(), values.mutable_data());
        const Vec3 origin = roi.frame.toPatient({v.originMm[0], v.originMm[1], v.originMm[2]});
        py::dict out;
        out["values"] = values;
        out["origin"] = py::make_tuple(origin.x, origin.y, origin.z);
        // In the array's own axis order (z, y, x), as rasterize() gives them.
        out["spacing"] = py::make_tuple(v.voxelMm[2], v.voxelMm[1], v.voxelMm[0]);
        out["directions"] =
            py::make_tuple(py::make_tuple(roi.frame.n.x, roi.frame.n.y, roi.frame.n.z),
                           py::make_tuple(roi.frame.v.x, roi.frame.v.y, roi.frame.v.z),
                           py::make_tuple(roi.frame.u.x, roi.frame.u.y, roi.frame.u.z));
        return out;
    });

    m.def("_surface_distance_maps",
          [](const std::vector<PyMesh*>& meshes, const std::vector<std::string>& names,
             double maxDistanceMm, int texels, double samplingMm, bool withPairs) {
              std::vector<TriangleSoup> soups;
              for (const PyMesh* mesh : meshes) {
                  if (mesh->surface.triangles.empty())
                      throw py::value_error("a mesh has no triangles");
                  soups.push_back(mesh->surface);
              }
              SceneMapsOptions options;
              options.atlas.sizeTexels = texels;
              options.atlas.maxErrorMm = samplingMm;
              if (maxDistanceMm > 0) options.query.maxDistanceMm = maxDistanceMm;
              options.proximity = withPairs;
              const SurfaceScene scene(std::move(soups), names);
              const SceneMaps maps = onDevice(
                  [&](ocl::Runtime& device) { return sceneDistanceMaps(device, scene, options); });
              py::list perMesh;
              for (std::size_t o = 0; o < maps.maps.size(); ++o) {
                  const std::vector<ClosestPrimitive>& vertices = maps.maps[o].vertices;
                  py::array_t<double> distance(py::ssize_t(vertices.size()));
                  py::array_t<std::int32_t> nearest(py::ssize_t(vertices.size()));
                  std::vector<Vec3> points(vertices.size());
                  for (std::size_t i = 0; i < vertices.size(); ++i) {
                      distance.mutable_data()[i] =
                          vertices[i].object < 0 ? INFINITY : vertices[i].distanceMm;
                      nearest.mutable_data()[i] = vertices[i].object;
                      points[i] = vertices[i].object < 0 ? Vec3{NAN, NAN, NAN} : vertices[i].point;
                  }
                  py::dict map;
                  map["name"] = scene.name(o);
                  map["distance_mm"] = distance;
                  map["nearest"] = nearest;
                  map["closest_point"] = pointsArray(points);
                  map["sampling_bound_mm"] = maps.samples[o].samplingBoundMm();
                  perMesh.append(map);
              }
              py::list pairs;
              for (const PairProximity& p : maps.pairs) {
                  py::dict pair;
                  pair["a"] = scene.name(p.first);
                  pair["b"] = scene.name(p.second);
                  pair["separation_mm"] = p.separationMm;
                  pair["separation_bound_mm"] = p.boundMm;
                  pair["surfaces_intersect"] = p.surfacesIntersect;
                  pair["a_inside_b"] = p.firstInsideSecond;
                  pair["b_inside_a"] = p.secondInsideFirst;
                  pair["colliding"] = p.colliding();
                  pair["penetration_mm"] = p.deepestPointMm;
                  pairs.append(pair);
              }
              return py::make_tuple(perMesh, pairs);
          });

    m.def("_compare", [](const PyMesh& a, const PyMesh& b, double spacingMm, double toleranceMm) {
        const ComparedSolid solidA = solidOf(a, "a"), solidB = solidOf(b, "b");
        const Comparison comparison = onDevice([&](ocl::Runtime& device) {
            return compareSolids(device, solidA, solidB, CompareOptions{spacingMm, toleranceMm});
        });
        return toPython(comparisonJson(comparison));
    });
    m.def("_segment", [](const PyMesh& mesh, int regions, const std::string& speed, bool disks) {
        const MeshGraph graph = MeshGraph::fromSoup(mesh.surface);
        if (regions < 1 || regions > graph.vertexCount())
            throw py::value_error("segment(): regions must be from 1 to the mesh's " +
                                  std::to_string(graph.vertexCount()) + " vertices");
        SegmentOptions options;
        options.regions = regions;
        options.speed = parseSpeedKind(speed);
        options.lloyd.diskConstraint = disks;
        Segmentation result;
        {
            py::gil_scoped_release release;
            result = segmentMesh(graph, options);
        }
        py::dict out;
        out["vertex_region"] = py::array_t<std::int32_t>(py::ssize_t(result.vertexRegion.size()),
                                                         result.vertexRegion.data());
        out["face_region"] = py::array_t<std::int32_t>(py::ssize_t(result.faceRegion.size()),
                                                       result.faceRegion.data());
        out["seeds"] = result.seeds;
        out["regions"] = toPython(segmentRegionsJson(result.regions));
        out["iterations"] = result.iterations;
        out["converged"] = result.converged;
        out["lloydEnergy"] = result.energy;
        out["seedsAddedForDisks"] = result.seedsAdded;
        out["curvatureWeightMm"] = result.curvatureWeightMm;
        return out;
    });

    m.def("_geodesic", [](const PyMesh& mesh, const std::vector<int>& from,
                          const std::string& speed, double curvatureWeightMm) {
        const MeshGraph graph = MeshGraph::fromSoup(mesh.surface);
        if (from.empty()) throw py::value_error("geodesic(): give at least one source vertex");
        std::vector<GeodesicSource> sources;
        for (const int v : from) {
            if (v < 0 || v >= graph.vertexCount())
                throw py::value_error("geodesic(): source vertex " + std::to_string(v) +
                                      " is not one of the mesh's " +
                                      std::to_string(graph.vertexCount()) + " vertices");
            sources.push_back({v, 0.0, int(sources.size())});
        }
        const SpeedKind kind = parseSpeedKind(speed);
        const double weight =
            curvatureWeightMm > 0 ? curvatureWeightMm : defaultCurvatureWeight(graph);
        // Fast marching on the host: the same distances as the program's
        // default on meshes of this size, and no device needed.
        GeodesicField field;
        {
            py::gil_scoped_release release;
            const UpdateStencils stencils(graph, UnfoldOptions{});
            const std::vector<double> speeds = curvatureSpeed(graph, kind, weight);
            field =
                geodesicDistances(stencils, sources, speeds, nullptr, GeodesicSolver::FastMarching);
        }
        py::array_t<double> distance(py::ssize_t(field.time.size()));
        double* d = distance.mutable_data();
        for (std::size_t v = 0; v < field.time.size(); ++v)
            d[v] = field.time[v] >= kUnreached ? std::numeric_limits<double>::infinity()
                                               : field.time[v];
        py::dict out;
        out["distance_mm"] = distance;
        out["nearest_source"] =
            py::array_t<std::int32_t>(py::ssize_t(field.label.size()), field.label.data());
        return out;
    });

    m.def("_compare_sets", [](const PyStructureSet& setA, const PyStructureSet& setB,
                              const std::vector<std::string>& matches, double spacingMm,
                              double toleranceMm) {
        const RoiMatching matching = matchRois(setA.read.contours, setB.read.contours, matches);
        nlohmann::ordered_json report{{"a", setA.source}, {"b", setB.source}};
        nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
        onDevice([&](ocl::Runtime& device) {
            for (const RoiPair& pair : matching.pairs)
                pairs.push_back(comparedPairRow(device, pair, setA.source, setB.source,
                                                CompareOptions{spacingMm, toleranceMm}));
            return 0;
        });
        report["pairs"] = pairs;
        report.update(unpairedJson(matching));
        return toPython(report);
    });

    m.def("_compare_contours", [](const PyStructureSet& setA, const py::object& roiA,
                                  const PyStructureSet& setB, const py::object& roiB,
                                  double spacingMm, double toleranceMm) {
        const Roi& a = chooseRoi(setA.read, roiA);
        const Roi& b = chooseRoi(setB.read, roiB);
        const Comparison comparison = onDevice([&](ocl::Runtime& device) {
            RoiSurface surfaceA = reconstructRoi(device, a);
            RoiSurface surfaceB = reconstructRoi(device, b);
            for (const auto* s : {&surfaceA, &surfaceB})
                if (!s->check.validSolid())
                    throw InvalidResult("ROI '" + (s == &surfaceA ? a.name : b.name) +
                                        "' gives no valid closed solid");
            return compareSolids(device,
                                 ComparedSolid{std::move(surfaceA.surface), surfaceA.check, &a},
                                 ComparedSolid{std::move(surfaceB.surface), surfaceB.check, &b},
                                 CompareOptions{spacingMm, toleranceMm});
        });
        return toPython(comparisonJson(comparison));
    });
}
