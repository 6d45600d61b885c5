#include "accel/bvh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/shared_math.h"

namespace wp {
namespace {

constexpr unsigned kMaxLeafSize = 4;
constexpr unsigned kMaxDepth = 32;  // within WP_BVH_STACK_SIZE (kernels/shared/bvh.h)
static_assert(kMaxLeafSize <= WP_BVH_MAX_LEAF_SIZE && 2 * kMaxDepth <= WP_BVH_STACK_SIZE);

// What Embree's callbacks build: nodes and leaves of our own, in its thread-local memory.
struct BuildNode {
    bool leaf = false;
    BuildNode* children[2] = {nullptr, nullptr};
    std::uint32_t triangles[kMaxLeafSize] = {};
    unsigned count = 0;
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int child_count, void*) {
    if (child_count > 2) return nullptr;
    return new (rtcThreadLocalAlloc(alloc, sizeof(BuildNode), 16)) BuildNode();
}

void set_children(void* node, void** children, unsigned int count, void*) {
    for (unsigned i = 0; i < count && i < 2; ++i)
        static_cast<BuildNode*>(node)->children[i] = static_cast<BuildNode*>(children[i]);
}

void set_bounds(void*, const RTCBounds**, unsigned int, void*) {}  // recomputed in double when flattening

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* primitives, size_t count, void*) {
    auto* leaf = new (rtcThreadLocalAlloc(alloc, sizeof(BuildNode), 16)) BuildNode();
    leaf->leaf = true;
    leaf->count = static_cast<unsigned>(count);
    for (size_t i = 0; i < count; ++i) leaf->triangles[i] = primitives[i].primID;
    std::sort(leaf->triangles, leaf->triangles + count);  // a leaf's order does not depend on the build's threads
    return leaf;
}

float round_down(double v) {
    float f = static_cast<float>(v);
    return double(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(double v) {
    float f = static_cast<float>(v);
    return double(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

struct Box {
    glm::dvec3 lower{std::numeric_limits<double>::infinity()}, upper{-std::numeric_limits<double>::infinity()};
    void add(const glm::dvec3& p) {
        lower = glm::min(lower, p);
        upper = glm::max(upper, p);
    }
    void add(const Box& b) {
        lower = glm::min(lower, b.lower);
        upper = glm::max(upper, b.upper);
    }
    // Rounded outward, so that the float box holds every double point of the box.
    std::array<float, 6> to_float() const {
        return {round_down(lower.x), round_down(lower.y), round_down(lower.z),
                round_up(upper.x),   round_up(upper.y),   round_up(upper.z)};
    }
};

// Flattens the subtree at `node` depth first; returns its box and the child word for its parent.
class Flattener {
 public:
    Flattener(const std::vector<TrianglePositions>& triangles, BvhTree& tree) : triangles_(triangles), tree_(tree) {}

    std::pair<Box, std::uint32_t> flatten(const BuildNode* node, int depth) {
        tree_.depth = std::max(tree_.depth, depth);
        if (node->leaf) return flatten_leaf(node);
        auto index = static_cast<std::uint32_t>(tree_.nodes.size());
        tree_.nodes.emplace_back();
        Box box;
        for (int i = 0; i < 2; ++i) {
            if (!node->children[i]) {
                tree_.nodes[index].child[i] = WP_BVH_NO_CHILD;
                continue;
            }
            auto [child_box, child_word] = flatten(node->children[i], depth + 1);
            tree_.nodes[index].bounds[i] = child_box.to_float();
            tree_.nodes[index].child[i] = child_word;
            box.add(child_box);
        }
        return {box, index};
    }

 private:
    std::pair<Box, std::uint32_t> flatten_leaf(const BuildNode* leaf) {
        auto first = static_cast<std::uint32_t>(tree_.leaf_order.size());
        Box box;
        for (unsigned i = 0; i < leaf->count; ++i) {
            tree_.leaf_order.push_back(leaf->triangles[i]);
            for (const glm::dvec3& p : triangles_[leaf->triangles[i]]) box.add(p);
        }
        return {box, WP_BVH_LEAF | first << WP_BVH_LEAF_COUNT_BITS | (leaf->count - 1)};
    }

    const std::vector<TrianglePositions>& triangles_;
    BvhTree& tree_;
};

struct EmbreeDevice {
    RTCDevice device;
    explicit EmbreeDevice(int threads) {
        std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
        device = rtcNewDevice(config.c_str());
        if (!device) throw std::runtime_error("Embree: cannot create a device");
    }
    ~EmbreeDevice() { rtcReleaseDevice(device); }
};

}  // namespace

BvhTree build_bvh(const std::vector<TrianglePositions>& triangles, int threads) {
    BvhTree tree;
    if (triangles.empty()) return tree;
    if (triangles.size() >= (std::size_t(1) << 28)) throw std::runtime_error("BVH: more than 2^28 triangles");
    EmbreeDevice device(threads);
    RTCBVH bvh = rtcNewBVH(device.device);
    std::vector<RTCBuildPrimitive> primitives(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        Box box;
        for (const glm::dvec3& p : triangles[i]) box.add(p);
        std::array<float, 6> b = box.to_float();
        primitives[i] = {b[0], b[1], b[2], 0u, b[3], b[4], b[5], static_cast<unsigned>(i)};
    }
    RTCBuildArguments arguments = rtcDefaultBuildArguments();
    arguments.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    arguments.maxBranchingFactor = 2;
    arguments.maxDepth = kMaxDepth;
    arguments.minLeafSize = 1;
    arguments.maxLeafSize = kMaxLeafSize;
    arguments.bvh = bvh;
    arguments.primitives = primitives.data();
    arguments.primitiveCount = primitives.size();
    arguments.primitiveArrayCapacity = primitives.size();
    arguments.createNode = create_node;
    arguments.setNodeChildren = set_children;
    arguments.setNodeBounds = set_bounds;
    arguments.createLeaf = create_leaf;
    auto* root = static_cast<BuildNode*>(rtcBuildBVH(&arguments));
    if (!root) {
        rtcReleaseBVH(bvh);
        throw std::runtime_error("Embree: the BVH build failed");
    }
    Flattener flattener(triangles, tree);
    if (root->leaf) {  // the root must be a node: one child, the leaf
        tree.nodes.emplace_back();
        auto [box, word] = flattener.flatten(root, 1);
        tree.nodes[0].bounds[0] = box.to_float();
        tree.nodes[0].child = {word, WP_BVH_NO_CHILD};
    } else {
        flattener.flatten(root, 1);
    }
    rtcReleaseBVH(bvh);  // frees every BuildNode
    return tree;
}

std::array<glm::dvec3, 3> vertex_normals(const Mesh& mesh, const glm::uvec3& t) {
    if (mesh.normals.empty()) return {};
    return {mesh.normals[t.x], mesh.normals[t.y], mesh.normals[t.z]};
}

std::array<glm::dvec2, 3> vertex_uvs(const Mesh& mesh, const glm::uvec3& t) {
    if (mesh.uvs.empty()) return {glm::dvec2(0.0, 0.0), glm::dvec2(1.0, 0.0), glm::dvec2(0.0, 1.0)};
    return {mesh.uvs[t.x], mesh.uvs[t.y], mesh.uvs[t.z]};
}

std::vector<TrianglePositions> scene_triangle_positions(const Scene& scene) {
    std::size_t count = 0;
    for (const Mesh& mesh : scene.meshes) count += mesh.triangles.size();
    std::vector<TrianglePositions> positions;
    positions.reserve(count);
    for (const Mesh& mesh : scene.meshes)
        for (const glm::uvec3& t : mesh.triangles)
            positions.push_back({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
    return positions;
}

}  // namespace wp
