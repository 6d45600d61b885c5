// Film files: written and read back bit for bit; truncated, corrupted, newer
// or foreign files refused with their messages; and the identity hash that
// decides which render may continue or merge a film.
#include "longrun/film_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "support/analytic_scenes.h"
#include "support/film_sums.h"
#include "support/meshes.h"
#include "support/temp_directory.h"
#include "support/thrown_message.h"

namespace wp {
namespace {

Film example_film(bool squares) {
    Film film = Film::empty(5, 3, 4, squares);
    film.items.end = 41;
    for (std::size_t i = 0; i < film.sums.size(); ++i) film.sums[i] = film_sum_from_float(float(i) * -0.37f + 2.0f);
    for (std::size_t i = 0; i < film.squares.size(); ++i) film.squares[i] = film_sum_from_float(float(i) * 1e20f);
    return film;
}

const RenderIdentity kIdentity{0x1234, 0x5678, "opencl"};

std::vector<char> file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// The FilmFileError message of reading `path`, "" if it reads.
std::string read_error(const std::string& path) {
    return test::thrown_message<FilmFileError>([&] { read_film_file(path); }, "");
}

class FilmFileTest : public ::testing::Test {
 protected:
    test::TempDirectory dir_{"film_file"};
    std::string path_ = dir_ / "film.wpfilm";
};

TEST_F(FilmFileTest, ReadsBackWhatWasWritten) {
    for (bool squares : {false, true}) {
        const Film film = example_film(squares);
        write_film_file(path_, {kIdentity, film});
        const FilmFile read = read_film_file(path_);
        EXPECT_EQ(read.identity, kIdentity);
        EXPECT_EQ(read.film.width, 5);
        EXPECT_EQ(read.film.height, 3);
        EXPECT_EQ(read.film.items, film.items);
        ASSERT_EQ(read.film.sums.size(), film.sums.size());
        EXPECT_TRUE(test::same_sums(read.film.sums, film.sums));
        ASSERT_EQ(read.film.squares.size(), film.squares.size());
        EXPECT_TRUE(test::same_sums(read.film.squares, film.squares));
    }
    EXPECT_EQ(dir_.entries(), std::vector<std::string>{"film.wpfilm"});  // no temporary left
}

// SPPM's photon estimate (flag bit 2) reads back exactly, footprints
// included, and a pixel without a visible point yet (radius and footprint
// 0, no photon) with it; a negative radius, or photons at a pixel of radius
// 0, are refused as corrupted.
Film film_with_photons() {
    Film film = example_film(false);
    film.photons = PhotonEstimate::start(15, 4096);
    for (std::size_t p = 0; p < 15; ++p) {
        if (p == 11) continue;  // no visible point yet
        film.photons.count[p] = double(p) * 0.5f;
        film.photons.radius[p] = 0.125 - double(p) * 1e-3f;
        film.photons.footprint[p] = 0.0625 - double(p) * 1e-3f;
        for (int c = 0; c < 3; ++c) film.photons.flux[3 * p + c] = double(p + c) * 0.3f;
    }
    return film;
}

TEST_F(FilmFileTest, SppmPhotonEstimatesReadBackAndBadOnesAreRefused) {
    Film film = film_with_photons();
    write_film_file(path_, {kIdentity, film});
    EXPECT_EQ(read_film_file(path_).film.photons, film.photons);
    film.photons.radius[7] = -0.125;
    write_film_file(path_, {kIdentity, film});
    EXPECT_EQ(read_error(path_),
              path_ + ": corrupted photon estimate (a count, radius, footprint or flux out of range)");
    film.photons.radius[7] = 0.0;
    write_film_file(path_, {kIdentity, film});
    EXPECT_EQ(read_error(path_),
              path_ + ": corrupted photon estimate (pixel 7 has photons or a footprint but no radius)");
}

// A version 3 film (before the footprints) still reads, its footprints 0
// (unknown), and there a radius of 0 is refused, as version 3 did.
TEST_F(FilmFileTest, Version3PhotonEstimatesStillRead) {
    Film film = film_with_photons();
    film.photons.radius[11] = 0.25;  // version 3 gave every pixel its radius from the start
    write_film_file(path_, {kIdentity, film});
    auto as_version_3 = [&] {  // the footprints' 15 doubles out, after the counts' and the radii's
        std::vector<char> bytes = file_bytes(path_);
        bytes[8] = 3;
        const std::size_t footprints = bytes.size() - 8 - 8 * 15 * (3 + 1);
        bytes.erase(bytes.begin() + std::ptrdiff_t(footprints), bytes.begin() + std::ptrdiff_t(footprints + 8 * 15));
        bytes.resize(bytes.size() - 8);
        const std::uint64_t checksum = fnv1a64(bytes.data(), bytes.size());
        bytes.insert(bytes.end(), reinterpret_cast<const char*>(&checksum),
                     reinterpret_cast<const char*>(&checksum) + 8);
        write_bytes(path_, bytes);
    };
    as_version_3();
    PhotonEstimate expected = film.photons;
    std::fill(expected.footprint.begin(), expected.footprint.end(), 0.0);
    EXPECT_EQ(read_film_file(path_).film.photons, expected);
    film.photons.radius[11] = 0.0;
    write_film_file(path_, {kIdentity, film});
    as_version_3();
    EXPECT_EQ(read_error(path_),
              path_ + ": corrupted photon estimate (a count, radius, footprint or flux out of range)");
}

// The estimator field holds 16 bytes: a name of all 16 reads back whole (it
// once lost its last byte, so "reference-double" came back "reference-doubl"
// and longer names collided with shorter ones); a longer one is refused when
// written, never cut.
TEST_F(FilmFileTest, EstimatorNamesOfSixteenBytesReadBackWholeAndLongerOnesAreRefused) {
    for (const char* name : {"opencl", "opencl-embree", "reference-float", "reference-double", "reference-embree"}) {
        write_film_file(path_, {{0x1234, 0x5678, name}, example_film(false)});
        EXPECT_EQ(read_film_file(path_).identity.estimator, name);
    }
    EXPECT_THROW(write_film_file(path_, {{0x1234, 0x5678, "reference-float-embree"}, example_film(false)}),
                 std::logic_error);
}

TEST_F(FilmFileTest, TruncatedFilesAreRefused) {
    write_film_file(path_, {kIdentity, example_film(true)});
    const std::vector<char> whole = file_bytes(path_);
    for (std::size_t size : {std::size_t(0), std::size_t(5), std::size_t(11), std::size_t(60), std::size_t(100),
                             whole.size() / 2, whole.size() - 1}) {
        write_bytes(path_, std::vector<char>(whole.begin(), whole.begin() + std::ptrdiff_t(size)));
        const std::string error = read_error(path_);
        EXPECT_TRUE(error.find("truncated") != std::string::npos ||
                    (size < 8 && error.find("not a wavepath film file") != std::string::npos))
            << size << ": " << error;
        EXPECT_EQ(error.rfind(path_ + ": ", 0), 0u) << error;
    }
}

TEST_F(FilmFileTest, CorruptedBytesFailTheChecksum) {
    write_film_file(path_, {kIdentity, example_film(false)});
    const std::vector<char> whole = file_bytes(path_);
    // The scene hash, a limb of the first sum, the last sum's top byte and the checksum itself.
    for (std::size_t at : {std::size_t(17), std::size_t(90), whole.size() - 9, whole.size() - 1}) {
        std::vector<char> bytes = whole;
        bytes[at] ^= 0x10;
        write_bytes(path_, bytes);
        EXPECT_EQ(read_error(path_), path_ + ": corrupted (checksum mismatch)") << at;
    }
    std::vector<char> longer = whole;
    longer.push_back('x');
    write_bytes(path_, longer);
    EXPECT_EQ(read_error(path_), path_ + ": corrupted (1 bytes after the checksum)");
}

TEST_F(FilmFileTest, NewerVersionsAndOtherFilesAreRefused) {
    write_film_file(path_, {kIdentity, example_film(false)});
    std::vector<char> bytes = file_bytes(path_);
    bytes[8] = 5;  // the version's low byte
    write_bytes(path_, bytes);
    EXPECT_EQ(read_error(path_), path_ + ": film format version 5 is newer than this wavepath reads (4)");
    test::write_text(path_, "P3\n1 1\n255\n0 0 0\n");
    EXPECT_EQ(read_error(path_), path_ + ": not a wavepath film file (no WPFILM signature)");
    EXPECT_EQ(read_error(dir_ / "missing.wpfilm"), dir_ / "missing.wpfilm" + ": cannot read the film file");
}

// An adaptive film: pixels 1, 2 and 4 of 15 in a round from 6 samples on,
// the others stopped earlier.
Film film_in_round() {
    Film film = example_film(true);
    film.items = {0, 0};
    film.samples_before = {4, 6, 6, 5, 6, 4, 4, 4, 5, 5, 4, 4, 4, 4, 4};
    film.round_pixels = {1, 2, 4};
    film.items = {18, 23};
    return film;
}

// The same bytes as version 1 would have written them (no round flag).
void rewrite_as_version_1(const std::string& path) {
    std::vector<char> bytes = file_bytes(path);
    bytes[8] = 1;
    bytes.resize(bytes.size() - 8);
    const std::uint64_t checksum = fnv1a64(bytes.data(), bytes.size());
    bytes.insert(bytes.end(), reinterpret_cast<const char*>(&checksum), reinterpret_cast<const char*>(&checksum) + 8);
    write_bytes(path, bytes);
}

TEST_F(FilmFileTest, AdaptiveRoundsReadBackAndVersion1FilesStillRead) {
    const Film film = film_in_round();
    write_film_file(path_, {kIdentity, film});
    const FilmFile read = read_film_file(path_);
    EXPECT_EQ(read.film.round_pixels, film.round_pixels);
    EXPECT_EQ(read.film.samples_before, film.samples_before);
    EXPECT_EQ(read.film.items, film.items);
    EXPECT_EQ(read.film.sample_counts(), film.sample_counts());
    EXPECT_TRUE(test::same_sums(read.film.squares, film.squares));

    const Film plain = example_film(true);
    write_film_file(path_, {kIdentity, plain});
    rewrite_as_version_1(path_);
    const FilmFile old = read_film_file(path_);
    EXPECT_EQ(old.film.items, plain.items);
    EXPECT_FALSE(old.film.in_round());
    EXPECT_TRUE(test::same_sums(old.film.sums, plain.sums));
    // Version 1 had no rounds: its flag is unknown there.
    write_film_file(path_, {kIdentity, film});
    rewrite_as_version_1(path_);
    EXPECT_EQ(read_error(path_), path_ + ": unknown flags 3");
}

// A round's table is checked after the checksum: pixels ascending, inside
// the film, holding the same samples before the round.
TEST_F(FilmFileTest, CorruptedRoundsAreRefused) {
    auto refused = [&](const Film& film) {
        write_film_file(path_, {kIdentity, film});
        return read_error(path_);
    };
    Film unsorted = film_in_round();
    unsorted.round_pixels = {2, 1, 4};
    EXPECT_EQ(refused(unsorted), path_ + ": corrupted adaptive round (pixel 1)");
    Film outside = film_in_round();
    outside.round_pixels = {1, 2, 15};
    EXPECT_EQ(refused(outside), path_ + ": corrupted adaptive round (pixel 15)");
    Film uneven = film_in_round();
    uneven.round_pixels = {1, 3};
    EXPECT_EQ(refused(uneven), path_ + ": corrupted adaptive round (pixel 3)");
    // fuzz_film: the empty table was read into a null pointer, which UBSan
    // reports (tests/fuzz/seeds/empty_round.wpfilm, run under it in CI).
    Film empty = film_in_round();
    empty.round_pixels = {};
    EXPECT_EQ(refused(empty), path_ + ": corrupted adaptive round (0 pixels)");
    write_film_file(path_, {kIdentity, film_in_round()});
    std::vector<char> bytes = file_bytes(path_);
    bytes.resize(bytes.size() - 20);
    write_bytes(path_, bytes);
    EXPECT_NE(read_error(path_).find("truncated"), std::string::npos) << read_error(path_);
}

TEST_F(FilmFileTest, FilmsOfAnotherRenderAreRefused) {
    const FilmFile file{kIdentity, example_film(false)};
    auto mismatch = [&](const RenderIdentity& identity, int width, int height) {
        try {
            check_film_matches("f.wpfilm", file, identity, width, height);
        } catch (const FilmFileError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(mismatch(kIdentity, 5, 3), "");
    EXPECT_EQ(mismatch(kIdentity, 6, 3), "f.wpfilm: a film of 5x3 pixels, this render is 6x3");
    EXPECT_EQ(mismatch(kIdentity, 5, 4), "f.wpfilm: a film of 5x3 pixels, this render is 5x4");  // each side
    EXPECT_EQ(mismatch({0x1234, 0x5678, "reference-float"}, 5, 3),
              "f.wpfilm: rendered by the opencl estimator, this render uses reference-float");
    EXPECT_EQ(mismatch({0x1235, 0x5678, "opencl"}, 5, 3),
              "f.wpfilm: rendered from another scene (its content differs)");
    EXPECT_EQ(mismatch({0x1234, 0x5679, "opencl"}, 5, 3),
              "f.wpfilm: rendered with other settings (max_depth, rr_depth, seed, nee, mis, hemisphere, sampler, "
              "adaptive sampling or the integrator and its settings differ)");
}

TEST(RenderIdentity, EverySettingThatChangesTheImageChangesIt) {
    Scene base = test::plane_under_square_light({}, {0.5, 0.5, 0.5}, {4, 4, 4}, 0.5, 1.0);
    base.meshes.push_back(test::unit_cube(0));
    base.meshes[0].normals.assign(base.meshes[0].positions.size(), glm::dvec3(0, 0, 1));
    const RenderIdentity identity = render_identity(base, "opencl");
    auto settings_changed = [&](auto change) {
        Scene scene = base;
        change(scene);
        return render_identity(scene, "opencl").settings != identity.settings;
    };
    EXPECT_TRUE(settings_changed([](Scene& s) { s.render.max_depth += 1; }));
    EXPECT_TRUE(settings_changed([](Scene& s) { s.render.rr_depth += 1; }));
    EXPECT_TRUE(settings_changed([](Scene& s) { s.render.seed += 1; }));
    EXPECT_TRUE(settings_changed([](Scene& s) { s.render.nee = !s.render.nee; }));
    EXPECT_TRUE(settings_changed([](Scene& s) { s.render.mis = !s.render.mis; }));
    EXPECT_TRUE(settings_changed([](Scene& s) { s.render.hemisphere = Hemisphere::Uniform; }));
    EXPECT_FALSE(settings_changed([](Scene& s) { s.render.spp += 1; }));  // a film can be continued to more samples

    auto scene_changed = [&](auto change) {
        Scene scene = base;
        change(scene);
        return render_identity(scene, "opencl").scene != identity.scene;
    };
    EXPECT_TRUE(scene_changed([](Scene& s) { s.camera.width += 1; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.camera.fov_y_degrees += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.materials[0].albedo.x += 1e-9; }));
    // A rough conductor's every parameter.
    auto parameter_changed = [&](auto change) {
        Scene a = base;
        a.materials[0].type = MaterialType::RoughConductor;
        Scene b = a;
        change(b.materials[0]);
        return render_identity(a, "opencl").scene != render_identity(b, "opencl").scene;
    };
    EXPECT_TRUE(parameter_changed([](Material& m) { m.eta.z += 1e-9; }));
    EXPECT_TRUE(parameter_changed([](Material& m) { m.k.x += 1e-9; }));
    EXPECT_TRUE(parameter_changed([](Material& m) { m.specular_reflectance.y -= 1e-9; }));
    EXPECT_TRUE(parameter_changed([](Material& m) { m.distribution = Microfacet::GGX; }));
    EXPECT_TRUE(parameter_changed([](Material& m) { m.alpha_u += 1e-9; }));
    EXPECT_TRUE(parameter_changed([](Material& m) { m.alpha_v += 1e-9; }));
    // A rough plastic's every parameter (its diffuse_reflectance is the albedo, its eta the ior).
    auto plastic_parameter_changed = [&](auto change) {
        Scene a = base;
        a.materials[0].type = MaterialType::RoughPlastic;
        Scene b = a;
        change(b.materials[0]);
        return render_identity(a, "opencl").scene != render_identity(b, "opencl").scene;
    };
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.albedo.y += 1e-9; }));
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.specular_reflectance.x -= 1e-9; }));
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.ior += 1e-9; }));
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.nonlinear = true; }));
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.distribution = Microfacet::GGX; }));
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.alpha_u += 1e-9; }));
    EXPECT_TRUE(plastic_parameter_changed([](Material& m) { m.type = MaterialType::Plastic; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.quads.at(0).edge1.z += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.background.y += 1e-9; }));
    // A directional light, its direction and its irradiance.
    EXPECT_TRUE(scene_changed([](Scene& s) { s.directional_lights.push_back({}); }));
    auto directional_changed = [&](auto change) {
        Scene a = base;
        a.directional_lights.push_back({});
        Scene b = a;
        change(b.directional_lights[0]);
        return render_identity(a, "opencl").scene != render_identity(b, "opencl").scene;
    };
    EXPECT_TRUE(directional_changed([](DirectionalLight& d) { d.direction.x += 1e-9; }));
    EXPECT_TRUE(directional_changed([](DirectionalLight& d) { d.irradiance.z += 1e-9; }));
    // A point light, its position and intensity, and a spot's cone.
    EXPECT_TRUE(scene_changed([](Scene& s) { s.point_lights.push_back({}); }));
    auto point_changed = [&](auto change) {
        Scene a = base;
        a.point_lights.push_back({{0, 2, 0}, glm::dvec3(1.0), SpotCone{}});
        Scene b = a;
        change(b.point_lights[0]);
        return render_identity(a, "opencl").scene != render_identity(b, "opencl").scene;
    };
    EXPECT_TRUE(point_changed([](PointLight& p) { p.position.y += 1e-9; }));
    EXPECT_TRUE(point_changed([](PointLight& p) { p.intensity.x += 1e-9; }));
    EXPECT_TRUE(point_changed([](PointLight& p) { p.cone.reset(); }));
    EXPECT_TRUE(point_changed([](PointLight& p) { p.cone->axis.x += 1e-9; }));
    EXPECT_TRUE(point_changed([](PointLight& p) { p.cone->cutoff_angle += 1e-9; }));
    EXPECT_TRUE(point_changed([](PointLight& p) { p.cone->beam_width += 1e-9; }));
    // An environment map: its texels, scale and frame.
    auto environment_changed = [&](auto change) {
        Scene a = base;
        a.environment_map = EnvironmentMap{"sky.exr", 2, 3, std::vector<float>(18, 0.5f), 1.0, glm::dmat3(1.0), ""};
        Scene b = a;
        change(*b.environment_map);
        return render_identity(a, "opencl").scene != render_identity(b, "opencl").scene;
    };
    EXPECT_TRUE(scene_changed(
        [](Scene& s) { s.environment_map = EnvironmentMap{"sky.exr", 2, 3, {}, 1.0, glm::dmat3(1.0), ""}; }));
    EXPECT_TRUE(environment_changed([](EnvironmentMap& m) { m.texels[7] += 1e-6f; }));
    EXPECT_TRUE(environment_changed([](EnvironmentMap& m) { m.scale += 1e-9; }));
    EXPECT_TRUE(environment_changed([](EnvironmentMap& m) { m.to_world[2][0] = 1e-9; }));
    // A mesh as loaded: one vertex, one normal, one triangle's corners, its material, and a mesh more.
    EXPECT_TRUE(scene_changed([](Scene& s) { s.meshes[0].positions[5].y += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.meshes[0].normals[3].x += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { std::swap(s.meshes[0].triangles[7].x, s.meshes[0].triangles[7].y); }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.meshes[0].material = 1; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.meshes.push_back(s.meshes[0]); }));
    EXPECT_FALSE(scene_changed([](Scene& s) { s.meshes[0].file = "elsewhere.obj"; }));
    EXPECT_FALSE(scene_changed([](Scene& s) { s.source = "elsewhere.json"; }));
}

TEST(RenderIdentity, EveryTextureParameterChangesIt) {
    Scene base = test::plane_under_square_light({}, {0.5, 0.5, 0.5}, {4, 4, 4}, 0.5, 1.0);
    Texture bitmap;
    bitmap.width = 2;
    bitmap.height = 1;
    bitmap.texels = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    base.textures = {bitmap, Texture{}};
    base.textures[1].type = TextureType::Checkerboard;
    base.materials[0].texture(TexturedParameter::Albedo) = 0;
    base.meshes.push_back(test::unit_cube(0));
    base.meshes[0].uvs.assign(base.meshes[0].positions.size(), glm::dvec2(0.5, 0.5));
    const RenderIdentity identity = render_identity(base, "opencl");
    auto scene_changed = [&](auto change) {
        Scene scene = base;
        change(scene);
        return render_identity(scene, "opencl").scene != identity.scene;
    };
    EXPECT_TRUE(scene_changed([](Scene& s) { s.textures[0].texels[4] += 1e-6f; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { std::swap(s.textures[0].width, s.textures[0].height); }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.textures[0].filter = TextureFilter::Nearest; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.textures[0].wrap = TextureWrap::Mirror; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.textures[0].to_uv[5] += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.textures[1].color0.y += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.textures[1].color1.z += 1e-9; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.materials[0].texture(TexturedParameter::Albedo) = 1; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.materials[0].texture(TexturedParameter::SpecularReflectance) = 1; }));
    EXPECT_TRUE(scene_changed([](Scene& s) { std::swap(s.materials[0].textures[0], s.materials[0].textures[1]); }));
    EXPECT_TRUE(scene_changed([](Scene& s) { s.meshes[0].uvs[2].y += 1e-9; }));
    EXPECT_FALSE(scene_changed([](Scene& s) { s.textures[0].file = "elsewhere.png"; }));
}

}  // namespace
}  // namespace wp
