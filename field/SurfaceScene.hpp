#pragma once
// Several meshes ("objects": organs, a target, a treatment head) ready for
// closest-primitive queries between them: each with its bounding volume
// hierarchy, whether it is a closed surface, and the pseudo-normals that
// sign distances to closed objects (Bærentzen & Aanæs: the angle-weighted
// normal at a vertex, the mean of the two face normals at an edge, the face
// normal inside a face; the sign of (p − closest)·n is then exact for a
// closed, consistently oriented manifold).
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "geometry/TriangleBvh.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

class SurfaceScene {
  public:
    /// Takes the objects (at least one triangle each) and prepares them.
    /// O(T log T) in all their triangles, plus a watertightness check each.
    explicit SurfaceScene(std::vector<TriangleSoup> objects, std::vector<std::string> names = {});

    /// Objects already known to be valid closed solids oriented outward
    /// (checked as they were built, as reconstructions are): no check again.
    struct KnownValidSolids {};
    /// The same scene without the watertightness checks: every object is
    /// taken as closed and outward. O(T log T).
    SurfaceScene(std::vector<TriangleSoup> objects, std::vector<std::string> names,
                 KnownValidSolids);

    std::size_t objectCount() const { return objects_.size(); }
    const TriangleSoup& object(std::size_t i) const { return objects_[i]->soup; }
    const TriangleBvh& bvh(std::size_t i) const { return *objects_[i]->bvh; }
    const std::string& name(std::size_t i) const { return objects_[i]->name; }
    /// Closed, manifold and consistently oriented (MeshCheck's watertight):
    /// distances to it are signed, negative inside.
    bool closed(std::size_t i) const { return objects_[i]->closed; }
    /// The outward pseudo-normal of `feature` of triangle t of object i
    /// (outward even when the file's faces point inwards).
    Vec3 pseudoNormal(std::size_t i, std::size_t t, TriangleFeature feature) const {
        return objects_[i]->pseudoNormals[t][std::size_t(feature)];
    }
    std::size_t triangleCount() const;

  private:
    void add(TriangleSoup soup, std::string name, bool closed, bool flip);

    struct Object {
        std::string name;
        TriangleSoup soup;
        std::unique_ptr<TriangleBvh> bvh;  // refers to soup, so objects stay put
        bool closed = false;
        std::vector<std::array<Vec3, 7>> pseudoNormals;  // per triangle, by TriangleFeature
    };
    std::vector<std::unique_ptr<Object>> objects_;
};

}  // namespace dfrecon
