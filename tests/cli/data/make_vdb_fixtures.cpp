// Writes the OpenVDB files of tests/cli/vdb_test.sh (not built with the project; run once):
//   g++ -std=c++20 make_vdb_fixtures.cpp -o make_vdb_fixtures -lopenvdb -ltbb -lImath-3_1
//   ./make_vdb_fixtures tests/cli/data
// fog.vdb: a fog volume (a sphere of radius 1 at (2, 2, 2), voxel 0.25); velocity.vdb: a vec3s
// grid (a rotation on 9^3 voxels); outside.vdb: a level set whose active values are all positive.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <string>
void put(const std::string& path, openvdb::GridBase::Ptr g) {
    openvdb::io::File f(path);
    f.setCompression(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
    f.write({g});
    f.close();
}
int main(int, char** argv) {
    openvdb::initialize();
    const std::string dir = argv[1];
    auto fog =
        openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(2.0f), 0.25f);
    openvdb::tools::sdfToFogVolume(*fog);
    fog->setName("density");
    put(dir + "/fog.vdb", fog);
    auto v = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    v->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j)
            for (int k = 0; k <= 8; ++k)
                v->tree().setValue(openvdb::Coord(i, j, k),
                                   openvdb::Vec3s(-0.25f * j, 0.25f * i, 0.0f));
    v->setName("velocity");
    put(dir + "/velocity.vdb", v);
    auto outside = openvdb::FloatGrid::create(0.75f);
    outside->setGridClass(openvdb::GRID_LEVEL_SET);
    outside->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    outside->setName("outside");
    for (int i = 0; i < 4; ++i) outside->tree().setValue(openvdb::Coord(i, 0, 0), 0.5f);
    put(dir + "/outside.vdb", outside);
}
