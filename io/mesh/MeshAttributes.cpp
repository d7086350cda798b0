#include "io/mesh/MeshAttributes.hpp"

#include <stdexcept>

namespace dfrecon {

namespace {

template <class Values>
void checkSize(const std::string& what, const std::string& name, const Values& values,
               std::size_t count) {
    if (values.size() != count)
        throw std::invalid_argument(what + " data '" + name + "' has " +
                                    std::to_string(values.size()) + " values for " +
                                    std::to_string(count) + " " + what + "s");
}

}  // namespace

void checkAttributeSizes(const MeshAttributes& a, std::size_t vertices, std::size_t faces) {
    for (const auto& [name, v] : a.vertexScalars) checkSize("vertex", name, v, vertices);
    for (const auto& [name, v] : a.vertexLabels) checkSize("vertex", name, v, vertices);
    for (const auto& [name, v] : a.vertexVectors) checkSize("vertex", name, v, vertices);
    if (!a.vertexColours.empty()) checkSize("vertex", "colours", a.vertexColours, vertices);
    for (const auto& [name, v] : a.faceLabels) checkSize("face", name, v, faces);
    if (!a.faceColours.empty()) checkSize("face", "colours", a.faceColours, faces);
}

}  // namespace dfrecon
