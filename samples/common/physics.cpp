#include "common/physics.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace samples {

using vkcollide::Float3;

const vkcollide::TriangleResponse* findResponse(std::span<const vkcollide::TriangleResponse> responses, std::uint32_t object,
                                                std::uint32_t triangle) {
    auto it = std::lower_bound(responses.begin(), responses.end(), std::pair{object, triangle},
                               [](const vkcollide::TriangleResponse& r, const std::pair<std::uint32_t, std::uint32_t>& key) {
                                   return std::pair{r.object, r.triangle} < key;
                               });
    return it != responses.end() && it->object == object && it->triangle == triangle ? &*it : nullptr;
}

// --- SoftBody ---------------------------------------------------------------------

SoftBody::SoftBody(std::span<const Float3> rest, const Vec3& position, float stiffness, float softness)
    : stiffness_(stiffness), softness_(softness) {
    Vec3 c = Vec3::Zero();
    for (const Float3& p : rest) c += toVec(p);
    c /= static_cast<float>(rest.size());
    Eigen::Matrix3f aqq = Eigen::Matrix3f::Zero();
    for (const Float3& p : rest) {
        const Vec3 q = toVec(p) - c;
        rest_offsets_.push_back(q);
        aqq += q * q.transpose();
        positions_.push_back(toFloat3(position + q));
    }
    inverse_aqq_ = aqq.inverse();
    velocities_.assign(rest.size(), Vec3::Zero());
    pushes_.assign(rest.size(), Vec3::Zero());
    push_counts_.assign(rest.size(), 0);
}

void SoftBody::push(std::uint32_t vertex, const Vec3& direction, float distance) {
    pushes_[vertex] += direction * distance;
    ++push_counts_[vertex];
}

void SoftBody::setVelocity(const Vec3& v) { std::fill(velocities_.begin(), velocities_.end(), v); }

Vec3 SoftBody::velocity() const {
    Vec3 v = Vec3::Zero();
    for (const Vec3& vi : velocities_) v += vi;
    return v / static_cast<float>(velocities_.size());
}

void SoftBody::addVelocity(const Vec3& dv) {
    for (Vec3& v : velocities_) v += dv;
}

Vec3 SoftBody::centre() const {
    Vec3 c = Vec3::Zero();
    for (const Float3& p : positions_) c += toVec(p);
    return c / static_cast<float>(positions_.size());
}

void SoftBody::step(float dt, const Vec3& gravity, float floor_y) {
    const std::size_t n = positions_.size();
    constexpr float kRestitution = 0.3f;
    std::vector<Vec3> predicted(n);
    for (std::size_t i = 0; i < n; ++i) {
        Vec3 x = toVec(positions_[i]);
        Vec3& v = velocities_[i];
        v += gravity * dt;
        if (push_counts_[i]) {
            // Collision: move out now, and bounce off with what was moving inwards.
            const Vec3 p = pushes_[i] / static_cast<float>(push_counts_[i]);
            x += p;
            positions_[i] = toFloat3(x);
            const float len = p.norm();
            if (len > 0) {
                const Vec3 d = p / len;
                const float vn = v.dot(d);
                if (vn < 0) v -= (1 + kRestitution) * vn * d;
            }
            pushes_[i].setZero();
            push_counts_[i] = 0;
        }
        predicted[i] = x + v * dt;
    }
    // Best rotation R (polar part of Apq) and best volume-preserving linear map A.
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : predicted) c += p;
    c /= static_cast<float>(n);
    Eigen::Matrix3f apq = Eigen::Matrix3f::Zero();
    for (std::size_t i = 0; i < n; ++i) apq += (predicted[i] - c) * rest_offsets_[i].transpose();
    Eigen::JacobiSVD<Eigen::Matrix3f> svd(apq, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3f u = svd.matrixU();
    if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) *= -1;
    const Eigen::Matrix3f r = u * svd.matrixV().transpose();
    Eigen::Matrix3f a = apq * inverse_aqq_;
    const float det = a.determinant();
    a = det > 1e-6f ? Eigen::Matrix3f(a / std::cbrt(det)) : r;
    const Eigen::Matrix3f t = softness_ * a + (1 - softness_) * r;
    float lowest = floor_y;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 goal = t * rest_offsets_[i] + c;
        const Vec3 x = predicted[i] + stiffness_ * (goal - predicted[i]);
        velocities_[i] = (x - toVec(positions_[i])) / dt * 0.998f;
        positions_[i] = toFloat3(x);
        lowest = std::min(lowest, x.y());
    }
    // The floor lifts the whole body (clamping single vertices would flatten its
    // underside into overlapping triangles) and stops it sinking, with some friction.
    if (lowest < floor_y) {
        for (std::size_t i = 0; i < n; ++i) {
            positions_[i].y += floor_y - lowest;
            Vec3& v = velocities_[i];
            v = Vec3(0.9f * v.x(), std::max(v.y(), 0.0f), 0.9f * v.z());
        }
    }
}

// --- RigidBody ----------------------------------------------------------------------

RigidBody RigidBody::boxLike(const Vec3& h) {
    RigidBody b;
    b.inverse_mass = 1.0f;
    const Vec3 h2 = h.cwiseProduct(h);
    b.inverse_inertia_body = Vec3(3.0f / (h2.y() + h2.z()), 3.0f / (h2.x() + h2.z()), 3.0f / (h2.x() + h2.y())).asDiagonal();
    return b;
}

Eigen::Matrix3f RigidBody::inverseInertiaWorld() const {
    const Eigen::Matrix3f r = orientation.toRotationMatrix();
    return r * inverse_inertia_body * r.transpose();
}

Vec3 RigidBody::velocityAt(const Vec3& point) const { return velocity + angular_velocity.cross(point - position); }

void RigidBody::applyImpulse(const Vec3& point, const Vec3& impulse) {
    if (inverse_mass == 0) return;
    velocity += impulse * inverse_mass;
    angular_velocity += inverseInertiaWorld() * (point - position).cross(impulse);
}

void RigidBody::integrate(float dt, const Vec3& gravity, float damping) {
    if (inverse_mass == 0) return;
    velocity = (velocity + gravity * dt) * (1 - damping);
    angular_velocity *= 1 - damping;
    position += velocity * dt;
    const Eigen::Quaternionf w(0, angular_velocity.x(), angular_velocity.y(), angular_velocity.z());
    orientation.coeffs() += 0.5f * dt * (w * orientation).coeffs();
    orientation.normalize();
}

vkcollide::Transform3x4 RigidBody::transform() const {
    const Eigen::Matrix3f r = orientation.toRotationMatrix();
    return {r(0, 0), r(0, 1), r(0, 2), position.x(), r(1, 0), r(1, 1), r(1, 2), position.y(), r(2, 0), r(2, 1), r(2, 2), position.z()};
}

void resolveContact(RigidBody& a, RigidBody* b, const Vec3& point, const Vec3& normal, float restitution, float friction) {
    const float inv_b = b ? b->inverse_mass : 0.0f;
    const float inv_sum = a.inverse_mass + inv_b;
    if (inv_sum == 0) return;
    auto relative = [&]() -> Vec3 {
        const Vec3 vb = b ? b->velocityAt(point) : Vec3(Vec3::Zero());
        return a.velocityAt(point) - vb;
    };
    // How much velocity an impulse of 1 along `dir` changes at the contact.
    auto response = [&](const Vec3& dir) {
        float k = inv_sum;
        k += dir.dot((a.inverseInertiaWorld() * (point - a.position).cross(dir)).cross(point - a.position));
        if (b && b->inverse_mass > 0) k += dir.dot((b->inverseInertiaWorld() * (point - b->position).cross(dir)).cross(point - b->position));
        return k;
    };
    const float vn = relative().dot(normal);
    if (vn < 0) {
        const float j = -(1 + restitution) * vn / response(normal);
        a.applyImpulse(point, j * normal);
        if (b) b->applyImpulse(point, -j * normal);
        // Coulomb friction against the sliding velocity, at most friction * j.
        const Vec3 vr = relative();
        const Vec3 vt = vr - vr.dot(normal) * normal;
        const float speed = vt.norm();
        if (speed > 1e-6f) {
            const Vec3 t = vt / speed;
            const float jt = std::min(speed / response(t), friction * j);
            a.applyImpulse(point, -jt * t);
            if (b) b->applyImpulse(point, jt * t);
        }
    }
}

void separate(RigidBody& a, RigidBody* b, const Vec3& normal, float distance) {
    const float inv_b = b ? b->inverse_mass : 0.0f;
    const float inv_sum = a.inverse_mass + inv_b;
    if (inv_sum == 0) return;
    a.position += normal * (distance * a.inverse_mass / inv_sum);
    if (b) b->position -= normal * (distance * inv_b / inv_sum);
}

// --- Cloth --------------------------------------------------------------------------

Cloth::Cloth(const vkcollide::HostMesh& grid, std::uint32_t nx, std::uint32_t ny, float friction)
    : positions_(grid.positions), friction_(friction) {
    for (const Float3& p : positions_) previous_.push_back(toVec(p));
    inverse_mass_.assign(positions_.size(), 1.0f);
    const auto at = [nx](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
    auto link = [&](std::uint32_t a, std::uint32_t b, float stiffness) {
        links_.push_back({a, b, (toVec(positions_[a]) - toVec(positions_[b])).norm(), stiffness});
    };
    for (std::uint32_t j = 0; j <= ny; ++j)
        for (std::uint32_t i = 0; i <= nx; ++i) {
            if (i < nx) link(at(i, j), at(i + 1, j), 1.0f);              // stretch
            if (j < ny) link(at(i, j), at(i, j + 1), 1.0f);
            if (i < nx && j < ny) {                                        // shear
                link(at(i, j), at(i + 1, j + 1), 0.2f);
                link(at(i + 1, j), at(i, j + 1), 0.2f);
            }
            if (i + 2 <= nx) link(at(i, j), at(i + 2, j), 0.02f);         // bending
            if (j + 2 <= ny) link(at(i, j), at(i, j + 2), 0.02f);
        }
}

void Cloth::setMass(float total) {
    const auto free = std::count_if(inverse_mass_.begin(), inverse_mass_.end(), [](float w) { return w > 0; });
    for (float& w : inverse_mass_)
        if (w > 0) w = static_cast<float>(free) / total;
}

void Cloth::push(std::uint32_t vertex, const Vec3& offset) {
    positions_[vertex] = toFloat3(toVec(positions_[vertex]) + offset);
    previous_[vertex] += offset;
}

void Cloth::step(float dt, const Vec3& gravity, int iterations) {
    const std::size_t n = positions_.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (inverse_mass_[i] == 0) continue;
        const Vec3 x = toVec(positions_[i]);
        const Vec3 v = (x - previous_[i]) * 0.99f;
        previous_[i] = x;
        positions_[i] = toFloat3(x + v + gravity * dt * dt);
    }
    for (int it = 0; it < iterations; ++it) {
        for (const Link& l : links_) {
            const Vec3 a = toVec(positions_[l.a]), b = toVec(positions_[l.b]);
            const Vec3 d = b - a;
            const float len = d.norm();
            const float wa = inverse_mass_[l.a], wb = inverse_mass_[l.b];
            if (len < 1e-9f || wa + wb == 0) continue;
            // Shared by inverse mass: half each between free vertices, all on the free one
            // next to a pinned one.
            positions_[l.a] = toFloat3(a + (len - l.rest) / len * (wa / (wa + wb)) * l.stiffness * d);
            positions_[l.b] = toFloat3(b - (len - l.rest) / len * (wb / (wa + wb)) * l.stiffness * d);
        }
        for (const Contact& c : contacts_) {
            const float wv = inverse_mass_[c.vertex], wb = c.body ? c.body->inverse_mass : 0.0f;
            if (wv + wb == 0) continue;
            Vec3 x = toVec(positions_[c.vertex]);
            const Vec3 point = c.body ? Vec3(c.point + c.body->position) : c.point;
            const float depth = c.normal.dot(x - point);
            if (depth >= c.thickness || depth < -c.reach) continue;  // apart, or too deep to trust
            const Vec3 correction = (c.thickness - depth) * c.normal;
            x += correction * (wv / (wv + wb));
            if (c.body) c.body->position -= correction * (wb / (wv + wb));
            if (it == iterations - 1 && wv > 0) {
                // Friction: take back part of this step's sliding along the plane.
                const Vec3 moved = x - previous_[c.vertex];
                x -= friction_ * (moved - moved.dot(c.normal) * c.normal);
            }
            positions_[c.vertex] = toFloat3(x);
        }
    }
}

}  // namespace samples
