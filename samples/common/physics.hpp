// Just enough physics to move the meshes plausibly: shape matching for deformable
// bodies, a rigid body with impulses, a position-based cloth. vkcollide supplies the
// contacts (pairs and response vectors); these helpers only turn them into motion.
#pragma once

#include "render/vk.hpp"  // before any vkcollide header (see vk.hpp)

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "vkcollide/mesh.hpp"
#include "vkcollide/narrow.hpp"
#include "vkcollide/scene.hpp"

namespace samples {

using Vec3 = Eigen::Vector3f;

inline Vec3 toVec(vkcollide::Float3 p) { return {p.x, p.y, p.z}; }
inline vkcollide::Float3 toFloat3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The response of (object, triangle) in DetectResult::responses (sorted), or null.
const vkcollide::TriangleResponse* findResponse(std::span<const vkcollide::TriangleResponse> responses, std::uint32_t object,
                                                std::uint32_t triangle);

// Shape matching (Müller, Heidelberger, Teschner, Gross 2005): every step the vertices
// are pulled towards the rest shape under the best rigid motion, blended with the best
// linear (volume-preserving) fit for a softer, squashier body.
class SoftBody {
public:
    // rest: object-space vertex positions; placed with its centre at `position`.
    // stiffness in (0, 1]: the share of the way to the goal per step; softness in [0, 1]:
    // how much of the linear fit is allowed.
    SoftBody(std::span<const vkcollide::Float3> rest, const Vec3& position, float stiffness, float softness);

    // A push of `distance` along `direction` on one vertex (a collision response); pushes
    // on one vertex are averaged, and velocity into the push is removed.
    void push(std::uint32_t vertex, const Vec3& direction, float distance);
    // Gravity, collision pushes, shape matching, a floor at y = floor_y (which lifts the
    // whole body).
    void step(float dt, const Vec3& gravity, float floor_y);
    void setVelocity(const Vec3& v);
    // The mean velocity of the vertices, and a change of every vertex's velocity (a
    // collision impulse on the whole body).
    Vec3 velocity() const;
    void addVelocity(const Vec3& dv);

    const std::vector<vkcollide::Float3>& positions() const { return positions_; }
    Vec3 centre() const;

private:
    std::vector<vkcollide::Float3> positions_;
    std::vector<Vec3> rest_offsets_, velocities_, pushes_;
    std::vector<std::uint32_t> push_counts_;
    Eigen::Matrix3f inverse_aqq_;
    float stiffness_, softness_;
};

// A rigid body: position, orientation, velocities, mass and inertia of a box that
// roughly encloses the mesh.
struct RigidBody {
    Vec3 position = Vec3::Zero(), velocity = Vec3::Zero(), angular_velocity = Vec3::Zero();
    Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
    float inverse_mass = 1.0f;  // 0: static
    Eigen::Matrix3f inverse_inertia_body = Eigen::Matrix3f::Identity();

    // Mass 1 and the inertia of a solid box with these half extents.
    static RigidBody boxLike(const Vec3& half_extents);
    Eigen::Matrix3f inverseInertiaWorld() const;
    Vec3 velocityAt(const Vec3& point) const;
    void applyImpulse(const Vec3& point, const Vec3& impulse);
    // Semi-implicit Euler with a little damping.
    void integrate(float dt, const Vec3& gravity, float damping);
    vkcollide::Transform3x4 transform() const;
};

// One contact between a and b (b may be null: the static world): `normal` points from b
// towards a. Removes approaching velocity at `point` (restitution, Coulomb friction).
// Resolving a list of contacts a few times over (sequential impulses) lets stacks rest.
void resolveContact(RigidBody& a, RigidBody* b, const Vec3& point, const Vec3& normal, float restitution, float friction);
// Moves a and b apart by `distance` along `normal` (from b towards a), split by inverse mass.
void separate(RigidBody& a, RigidBody* b, const Vec3& normal, float distance);

// A position-based cloth (Müller et al. 2007): particles, stretch and shear constraints
// along the grid, bending constraints across two cells.
class Cloth {
public:
    // The vertices and triangles of a clothGrid(nx, ny) mesh already placed in the world.
    // friction in [0, 1]: the share of sliding a contact removes per step.
    Cloth(const vkcollide::HostMesh& grid, std::uint32_t nx, std::uint32_t ny, float friction);

    // A body that moves only by translation (a ball) and that contacts can push back:
    // its position is moved by the steps' contacts, so (position - position before the
    // step) / dt is its velocity with the cloth's pushes in it.
    struct Body {
        Vec3 position = Vec3::Zero();
        float inverse_mass = 1.0f;
    };
    // A collision response: vertex `vertex` must stay at least `thickness` in front of
    // the plane through `point` with unit normal `normal`; a vertex more than `reach`
    // behind it is left alone (the plane is only a local approximation). With a body,
    // `point` is relative to the body's position (the plane moves with it), and the
    // correction is shared by inverse mass: the body takes the opposite of the vertex's,
    // so momentum is kept and the cloth slows the body as much as the body moves the cloth.
    struct Contact {
        std::uint32_t vertex;
        Vec3 point, normal;
        float thickness, reach;
        Body* body = nullptr;
    };
    // The contacts the next steps enforce, inside the solver (after the other constraints
    // of each iteration), so stretching cannot pull the cloth back through them.
    void setContacts(std::vector<Contact> contacts) { contacts_ = std::move(contacts); }
    // Moves a vertex now by `offset` (a one-off response) without giving it velocity.
    void push(std::uint32_t vertex, const Vec3& offset);
    void step(float dt, const Vec3& gravity, int iterations);
    const std::vector<vkcollide::Float3>& positions() const { return positions_; }
    // The cloth's mass, spread evenly over its free vertices (each vertex weighs 1 until
    // this is called: only ratios matter to the cloth alone, masses to a Body).
    void setMass(float total);
    // A vertex held where it is (a corner or edge tied down): nothing moves it.
    void pin(std::uint32_t vertex) { inverse_mass_[vertex] = 0; }
    bool pinned(std::uint32_t vertex) const { return inverse_mass_[vertex] == 0; }

private:
    struct Link {
        std::uint32_t a, b;
        float rest, stiffness;
    };
    std::vector<vkcollide::Float3> positions_;
    std::vector<Vec3> previous_;
    std::vector<float> inverse_mass_;
    std::vector<Link> links_;
    std::vector<Contact> contacts_;
    float friction_;
};

}  // namespace samples
