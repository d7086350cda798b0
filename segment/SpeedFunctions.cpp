#include "segment/SpeedFunctions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dfrecon {

const char* toString(SpeedKind kind) {
    for (const auto& [name, value] : kSpeedKindNames)
        if (value == kind) return name;
    return "?";
}

SpeedKind parseSpeedKind(const std::string& name) {
    std::string names;
    for (const auto& [known, value] : kSpeedKindNames) {
        if (name == known) return value;
        names += std::string(names.empty() ? "" : ", ") + known;
    }
    throw std::invalid_argument("unknown speed '" + name + "' (use " + names + ")");
}

double defaultCurvatureWeight(const MeshGraph& graph, int regions) {
    return std::sqrt(graph.totalArea() / std::max(regions, 1));
}

std::vector<double> totalCurvature(const MeshGraph& graph) {
    const std::size_t n = std::size_t(graph.vertexCount());
    std::vector<Vec3> laplacian(n);         // Σ (cot α + cot β)(x_j − x_i)
    std::vector<double> mixedArea(n, 0.0);  // Meyer et al.'s A_mixed
    std::vector<double> angleSum(n, 0.0);
    std::vector<char> onBoundary(n, 0);
    for (int t = 0; t < graph.triangleCount(); ++t) {
        const auto& tri = graph.triangle(t);
        std::array<Vec3, 3> p{};
        for (int k = 0; k < 3; ++k) p[std::size_t(k)] = graph.point(tri[std::size_t(k)]);
        const double area = graph.triangleArea(t);
        if (area <= 0) continue;
        std::array<double, 3> cot{}, angle{};
        for (int k = 0; k < 3; ++k) {
            const Vec3 u = p[std::size_t((k + 1) % 3)] - p[std::size_t(k)];
            const Vec3 w = p[std::size_t((k + 2) % 3)] - p[std::size_t(k)];
            cot[std::size_t(k)] = dot(u, w) / length(cross(u, w));
            angle[std::size_t(k)] = std::atan2(length(cross(u, w)), dot(u, w));
        }
        const bool obtuse = angle[0] > M_PI / 2 || angle[1] > M_PI / 2 || angle[2] > M_PI / 2;
        for (int k = 0; k < 3; ++k) {
            const std::size_t i = std::size_t(tri[std::size_t(k)]);
            const int j = (k + 1) % 3, l = (k + 2) % 3;
            const Vec3 eij = p[std::size_t(j)] - p[std::size_t(k)];
            const Vec3 eil = p[std::size_t(l)] - p[std::size_t(k)];
            // Edge k→j is opposite corner l, edge k→l opposite corner j.
            laplacian[i] = laplacian[i] + cot[std::size_t(l)] * eij + cot[std::size_t(j)] * eil;
            angleSum[i] += angle[std::size_t(k)];
            if (!obtuse)
                mixedArea[i] +=
                    (dot(eij, eij) * cot[std::size_t(l)] + dot(eil, eil) * cot[std::size_t(j)]) / 8;
            else
                mixedArea[i] += angle[std::size_t(k)] > M_PI / 2 ? area / 2 : area / 4;
            if (graph.neighbour(t, j) < 0 || graph.neighbour(t, l) < 0) onBoundary[i] = 1;
        }
    }
    std::vector<double> kappa(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        if (onBoundary[v] || mixedArea[v] <= 0) continue;
        const double h = length(laplacian[v]) / (4 * mixedArea[v]);  // |H|
        const double k = (2 * M_PI - angleSum[v]) / mixedArea[v];
        kappa[v] = k >= 0 ? 2 * h : 2 * std::sqrt(h * h - k);
    }
    return kappa;
}

std::vector<double> curvatureSpeed(const MeshGraph& graph, SpeedKind kind, double weightMm) {
    std::vector<double> speed(std::size_t(graph.vertexCount()), 1.0);
    if (kind == SpeedKind::Uniform) return speed;
    if (weightMm <= 0) weightMm = defaultCurvatureWeight(graph);
    const std::vector<double> kappa = totalCurvature(graph);
    for (std::size_t v = 0; v < speed.size(); ++v)
        speed[v] = kind == SpeedKind::EdgeRepulsive ? 1 + weightMm * kappa[v]
                                                    : 1 / (1 + weightMm * kappa[v]);
    return speed;
}

std::vector<double> scalarGradientSpeed(const MeshGraph& graph, const std::vector<double>& values,
                                        double weight) {
    const std::size_t n = std::size_t(graph.vertexCount());
    if (values.size() != n)
        throw std::invalid_argument("scalar has " + std::to_string(values.size()) + " values for " +
                                    std::to_string(n) + " vertices");
    if (!(weight >= 0)) throw std::invalid_argument("scalar speed weight must be ≥ 0");
    std::vector<double> gradientSum(n, 0.0), areaSum(n, 0.0);
    for (int t = 0; t < graph.triangleCount(); ++t) {
        const auto& tri = graph.triangle(t);
        const Vec3 p0 = graph.point(tri[0]);
        const Vec3 e1 = graph.point(tri[1]) - p0, e2 = graph.point(tri[2]) - p0;
        const Vec3 normal = cross(e1, e2);
        const double twiceArea = length(normal);
        if (twiceArea <= 0) continue;
        // ∇I of the linear interpolant: Σ I_k (n × e_k) / (2A), e_k opposite k.
        const Vec3 unit = (1 / twiceArea) * normal;
        Vec3 gradient{};
        for (int k = 0; k < 3; ++k) {
            const Vec3 opposite = graph.point(tri[std::size_t((k + 2) % 3)]) -
                                  graph.point(tri[std::size_t((k + 1) % 3)]);
            gradient = gradient + (values[std::size_t(tri[std::size_t(k)])] / twiceArea) *
                                      cross(unit, opposite);
        }
        const double magnitude = length(gradient), area = twiceArea / 2;
        for (int v : tri) {
            gradientSum[std::size_t(v)] += area * magnitude;
            areaSum[std::size_t(v)] += area;
        }
    }
    std::vector<double> speed(n, 1.0);
    for (std::size_t v = 0; v < n; ++v)
        if (areaSum[v] > 0) speed[v] = 1 / (1 + weight * gradientSum[v] / areaSum[v]);
    return speed;
}

}  // namespace dfrecon
