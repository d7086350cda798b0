// The one table of mesh formats: extensions in any case, names, which are
// read, and the lists messages and --help show.
#include <gtest/gtest.h>

#include "io/mesh/MeshFormat.hpp"

using namespace dfrecon;

TEST(MeshFormat, ExtensionsAndNamesMapBothWays) {
    EXPECT_EQ(meshFormatOfPath("/a/b.PLY"), MeshFormat::Ply);
    EXPECT_EQ(meshFormatOfPath("x.tar.vtp"), MeshFormat::Vtp);
    EXPECT_EQ(meshFormatOfPath("x.Vtk"), MeshFormat::Vtk);
    EXPECT_FALSE(meshFormatOfPath("x.xyz"));
    EXPECT_FALSE(meshFormatOfPath("folder"));
    EXPECT_FALSE(meshFormatOfPath("x."));
    for (const std::string& name : meshFormatNames(false)) {
        const std::optional<MeshFormat> format = meshFormatNamed(name);
        ASSERT_TRUE(format) << name;
        EXPECT_EQ(meshFormatName(*format), name);
        EXPECT_EQ(meshFormatExtension(*format), "." + name);
        EXPECT_EQ(meshFormatOfPath("a." + name), format);
    }
    EXPECT_FALSE(meshFormatNamed("PLY"));  // --format names are lower case
}

TEST(MeshFormat, OnlyOpenMeshFormatsAreRead) {
    EXPECT_TRUE(isReadableMeshFormat(MeshFormat::Stl));
    EXPECT_FALSE(isReadableMeshFormat(MeshFormat::Vtk));
    EXPECT_FALSE(isReadableMeshFormat(MeshFormat::Vtp));
    EXPECT_EQ(meshFormatList(true), "ply, obj, off or stl");
    EXPECT_EQ(meshFormatList(false), "ply, obj, off, stl, vtk or vtp");
    EXPECT_EQ(meshExtensionList(true), ".ply .obj .off .stl");
    EXPECT_EQ(meshExtensionList(false), ".ply .obj .off .stl .vtk .vtp");
}
