#include "analysis/force_flow.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <string>

#include "analysis/equilibrium_analysis.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"

namespace ashlar {

namespace {


// Random draws built from the engine's raw bits only: the standard
// library's distributions differ between implementations, and traces must
// be the same everywhere for a given seed.
class RandomDraws {
public:
  explicit RandomDraws(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1): the top 53 bits of one engine output.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Exponential with mean 1; 1 - u lies in (0, 1], so the log is finite.
  double exponential() { return -std::log(1.0 - uniform()); }

private:
  std::mt19937_64 engine_;
};

void check_options(const ForceFlowOptions& options) {
  if (options.traces < 1) {
    throw InvalidArgument("trace_loads: traces must be at least 1, got " +
                          std::to_string(options.traces));
  }
  if (options.max_steps < 0) {
    throw InvalidArgument(
        "trace_loads: max_steps must be >= 0 (0: 4 x the number of blocks), got " +
        std::to_string(options.max_steps));
  }
}

// Triangles (indices into `loop`) covering a simple counter-clockwise 2D
// polygon. Ears are clipped at the second remaining corner first, so a
// convex polygon gets the fan from its first corner; a non-convex one
// (contacts of non-convex blocks) still gets triangles inside it.
std::vector<std::array<int, 3>> triangulate(const Loop2& loop) {
  const auto cross = [](const Vec2& o, const Vec2& p, const Vec2& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  std::vector<int> left(loop.size());
  std::iota(left.begin(), left.end(), 0);
  std::vector<std::array<int, 3>> triangles;
  while (left.size() > 3) {
    const size_t m = left.size();
    size_t ear = 1;  // when rounding hides every ear, clip here anyway so the loop ends
    for (size_t k = 1; k <= m; ++k) {
      const size_t i = k % m;
      const Vec2& prev = loop[left[(i + m - 1) % m]];
      const Vec2& corner = loop[left[i]];
      const Vec2& next = loop[left[(i + 1) % m]];
      if (cross(prev, corner, next) < 0.0) continue;  // reflex corner
      bool empty = true;
      for (size_t j = 0; j < m && empty; ++j) {
        const Vec2& p = loop[left[j]];
        empty = !(cross(prev, corner, p) > 0.0 && cross(corner, next, p) > 0.0 &&
                  cross(next, prev, p) > 0.0);
      }
      if (empty) {
        ear = i;
        break;
      }
    }
    triangles.push_back({left[(ear + m - 1) % m], left[ear], left[(ear + 1) % m]});
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  if (left.size() == 3) triangles.push_back({left[0], left[1], left[2]});
  return triangles;
}

struct ContactTriangle {
  std::array<int, 3> corners;  // indices into the interface's vertices
  double area = 0.0;           // m^2
};

std::vector<ContactTriangle> contact_triangles(const Interface& contact) {
  Loop2 loop;
  for (const Vec3& p : contact.vertices) {
    loop.emplace_back((p - contact.center).dot(contact.u), (p - contact.center).dot(contact.v));
  }
  std::vector<ContactTriangle> out;
  for (const std::array<int, 3>& corners : triangulate(loop)) {
    const Vec3& p0 = contact.vertices[corners[0]];
    const double area =
        0.5 * (contact.vertices[corners[1]] - p0).cross(contact.vertices[corners[2]] - p0).norm();
    out.push_back({corners, area});
  }
  return out;
}

// A uniform point of the block's volume, by rejection in its bounding box.
Vec3 random_point_inside(const Block& block, RandomDraws& draws) {
  // A valid block fills a fair part of its box; this many misses means
  // the volume test is failing, not bad luck.
  constexpr int kMaxAttempts = 1000000;
  const Box3& box = block.bounds();
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    // One draw per statement: argument evaluation order is unspecified.
    const double x = draws.uniform();
    const double y = draws.uniform();
    const double z = draws.uniform();
    const Vec3 point = box.lo + (box.hi - box.lo).cwiseProduct(Vec3(x, y, z));
    if (contains_point(block, point)) return point;
  }
  throw Error("trace_loads: found no point inside block '" + block.name() + "' in " +
              std::to_string(kMaxAttempts) + " samples of its bounding box");
}

// Where a trace goes next: a point on one of the current block's
// interfaces and the direction of the force passed on there.
struct TraceStep {
  int interface = -1;
  int next_block = -1;
  Vec3 point = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
};

// The optimum's response to forces on single blocks, restricted to each
// block's own contact vertices, and the sampling of the next trace point.
class LoadTracer {
public:
  LoadTracer(const Structure& structure, const EquilibriumProblem& problem,
             const EquilibriumSolver& solver, const std::vector<Interface>& interfaces)
      : structure_(structure),
        problem_(problem),
        solver_(solver),
        interfaces_(interfaces),
        first_group_(interfaces.size(), -1),
        triangles_(interfaces.size()),
        interfaces_of_block_(structure.size()),
        response_(structure.size()),
        response_ready_(structure.size(), false) {
    // Contact vertex groups come interface by interface, in vertex order.
    for (int k = 0; k < problem.contact_vertex_count; ++k) {
      const ForceGroup& vertex = problem.groups[k];
      if (first_group_[vertex.source] >= 0) continue;
      first_group_[vertex.source] = k;
      triangles_[vertex.source] = contact_triangles(interfaces[vertex.source]);
      interfaces_of_block_[vertex.block_a].push_back(vertex.source);
      interfaces_of_block_[vertex.block_b].push_back(vertex.source);
    }
  }

  // The next step of a trace carrying a force along unit `direction` at
  // `point` on block `block`, leaving by any of its interfaces but
  // `excluded` (-1: none); none when the block passes nothing on.
  std::optional<TraceStep> step(int block, const Vec3& point, const Vec3& direction,
                                int excluded, RandomDraws& draws) {
    const Eigen::VectorXd rows = point_force_rows(problem_, structure_, block, direction, point);
    const Eigen::VectorXd change = response(block) * rows;

    // Per vertex, the magnitude of the force the block passes on when it
    // presses harder into the neighbour there (0 elsewhere); per interface
    // the sum of those forces; per triangle the probability weight.
    struct Candidate {
      int local_interface;  // index into interfaces_of_block_[block]
      const ContactTriangle* triangle;
      double weight;
    };
    std::vector<Candidate> candidates;
    std::vector<std::vector<double>> vertex_weights;
    std::vector<Vec3> passed;
    double total = 0.0;
    Eigen::Index offset = 0;
    for (int i : interfaces_of_block_[block]) {
      const Interface& contact = interfaces_[i];
      const double side = contact.a == block ? 1.0 : -1.0;  // the force on b acts on a reversed
      std::vector<double>& weights = vertex_weights.emplace_back(contact.vertices.size(), 0.0);
      Vec3& sum = passed.emplace_back(Vec3::Zero());
      for (size_t j = 0; j < contact.vertices.size(); ++j, offset += 4) {
        const Eigen::Vector4d x = change.segment<4>(offset);
        const double pressing = x(0) - x(1);
        if (!(pressing > 0.0)) continue;
        const Vec3 outgoing =
            side * (pressing * contact.normal + x(2) * contact.u + x(3) * contact.v);
        weights[j] = outgoing.norm();
        sum += outgoing;
      }
      if (i == excluded) continue;
      for (const ContactTriangle& triangle : triangles_[i]) {
        const std::array<int, 3>& c = triangle.corners;
        const double weight =
            triangle.area * (weights[c[0]] + weights[c[1]] + weights[c[2]]) / 3.0;
        if (!(weight > 0.0)) continue;
        candidates.push_back({static_cast<int>(vertex_weights.size() - 1), &triangle, weight});
        total += weight;
      }
    }
    if (!(total > 0.0)) return std::nullopt;

    double pick = draws.uniform() * total;
    const Candidate* chosen = &candidates.back();  // rounding may leave pick just above the sum
    for (const Candidate& candidate : candidates) {
      if (pick < candidate.weight) {
        chosen = &candidate;
        break;
      }
      pick -= candidate.weight;
    }
    const int local = chosen->local_interface;
    const int i = interfaces_of_block_[block][local];
    const Interface& contact = interfaces_[i];
    const std::array<int, 3>& corners = chosen->triangle->corners;
    const std::vector<double>& weights = vertex_weights[local];

    // A density linear in the corner weights over the triangle: a corner j
    // with probability w_j / sum w, then barycentric coordinates from
    // Dirichlet(2, 1, 1) with the 2 at corner j (density proportional to
    // its coordinate), as normalised sums of unit exponentials.
    double corner_pick =
        draws.uniform() * (weights[corners[0]] + weights[corners[1]] + weights[corners[2]]);
    int heavy = 2;
    for (int c = 0; c < 2; ++c) {
      if (corner_pick < weights[corners[c]]) {
        heavy = c;
        break;
      }
      corner_pick -= weights[corners[c]];
    }
    std::array<double, 3> coordinates;
    const double e1 = draws.exponential();
    const double e2 = draws.exponential();
    const double e3 = draws.exponential();
    const double e4 = draws.exponential();
    coordinates[heavy] = e1 + e2;
    coordinates[(heavy + 1) % 3] = e3;
    coordinates[(heavy + 2) % 3] = e4;
    const double sum = coordinates[0] + coordinates[1] + coordinates[2];

    TraceStep next;
    next.interface = i;
    next.next_block = contact.a == block ? contact.b : contact.a;
    for (int c = 0; c < 3; ++c) next.point += coordinates[c] / sum * contact.vertices[corners[c]];
    next.direction = passed[local].normalized();
    return next;
  }

private:
  // Rows: 4 per contact vertex of the block's interfaces (in
  // interfaces_of_block_ and vertex order), scaled dx; columns: the
  // block's balance rows. Solved once per block, on first use.
  const Eigen::MatrixXd& response(int block) {
    if (response_ready_[block]) return response_[block];
    Eigen::Index vertices = 0;
    for (int i : interfaces_of_block_[block]) vertices += interfaces_[i].vertices.size();
    Eigen::MatrixXd& out = response_[block];
    out.resize(4 * vertices, problem_.block_rows);
    for (int r = 0; r < problem_.block_rows; ++r) {
      Eigen::VectorXd unit = Eigen::VectorXd::Zero(problem_.row_count);
      unit(problem_.row_of_block[block] + r) = 1.0;
      const Eigen::VectorXd multipliers = solver_.multiplier_response(unit);
      Eigen::Index offset = 0;
      for (int i : interfaces_of_block_[block]) {
        for (size_t j = 0; j < interfaces_[i].vertices.size(); ++j, offset += 4) {
          out.block<4, 1>(offset, r) =
              solver_.group_response(problem_, first_group_[i] + static_cast<int>(j), multipliers);
        }
      }
    }
    response_ready_[block] = true;
    return out;
  }

  const Structure& structure_;
  const EquilibriumProblem& problem_;
  const EquilibriumSolver& solver_;
  const std::vector<Interface>& interfaces_;
  std::vector<int> first_group_;  // per interface, -1 when not in the problem
  std::vector<std::vector<ContactTriangle>> triangles_;  // per interface in the problem
  std::vector<std::vector<int>> interfaces_of_block_;
  std::vector<Eigen::MatrixXd> response_;
  std::vector<bool> response_ready_;
};

}  // namespace

Eigen::VectorXd point_force_rows(const EquilibriumProblem& problem, const Structure& structure,
                                 int block, const Vec3& force, const Vec3& at) {
  const Eigen::Matrix<double, 6, 1> external =
      applied_force_rhs(force, at, &structure.block(block).centroid(), problem.weight_unit,
                        problem.length_unit);
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  Eigen::VectorXd out(problem.block_rows);
  for (int r = 0; r < problem.block_rows; ++r) out(r) = external(rows[r]);
  return out;
}

bool contains_point(const Block& block, const Vec3& point) {
  // Solid angle of each fan triangle (Van Oosterom and Strackee); a fan of
  // a planar face, convex or not, adds up to the face's solid angle.
  double solid_angle = 0.0;
  for (const FaceLoop& face : block.faces()) {
    const Vec3 a = block.vertices()[face[0]] - point;
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3 b = block.vertices()[face[k]] - point;
      const Vec3 c = block.vertices()[face[k + 1]] - point;
      const double la = a.norm(), lb = b.norm(), lc = c.norm();
      const double numerator = a.dot(b.cross(c));
      const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
      solid_angle += 2.0 * std::atan2(numerator, denominator);
    }
  }
  return solid_angle > 2.0 * kPi;  // winding number above 1/2
}

ForceFlow trace_loads(const Structure& structure, int block, const ForceFlowOptions& options,
                      const AnalysisSettings& settings) {
  const auto start = Clock::now();
  check_free_block(structure, block, "trace_loads");
  check_options(options);
  ForceFlow flow;
  EquilibriumAnalysis analysis(structure, settings);
  flow.analysis = analysis.solve();
  const EquilibriumProblem& problem = analysis.problem();
  check_analysed_block(problem, structure, block, "trace_loads");
  flow.stable = flow.analysis.stable;
  flow.support_interface.assign(options.traces, -1);
  flow.lost = options.traces;
  // The response reuses the analysis's factorisation pattern.
  const EquilibriumSolver& solver = analysis.solver();
  if (!analysis.prepare_response()) {
    flow.seconds = seconds_since(start);
    return flow;
  }
  flow.valid = true;

  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(settings.problem.contact);

  const std::vector<Interface>& interfaces = *interfaces_list;
  LoadTracer tracer(structure, problem, solver, interfaces);
  RandomDraws draws(options.seed);
  const int max_steps = options.max_steps > 0 ? options.max_steps : 4 * structure.size();
  const Block& traced = structure.block(block);
  std::map<int, int> traces_at;  // support interface -> traces that reached it
  flow.polylines.reserve(options.traces);
  for (int t = 0; t < options.traces; ++t) {
    Vec3 point = options.start == TraceStart::centroid ? traced.centroid()
                                                       : random_point_inside(traced, draws);
    Vec3 direction(0.0, 0.0, -1.0);
    int current = block;
    int came_through = -1;  // the interface by which the trace entered `current`
    std::vector<Vec3>& polyline = flow.polylines.emplace_back(1, point);
    for (int s = 0; s < max_steps; ++s) {
      const std::optional<TraceStep> next =
          tracer.step(current, point, direction, options.turn_back ? -1 : came_through, draws);
      if (!next) break;
      polyline.push_back(next->point);
      if (structure.is_support(next->next_block)) {
        flow.support_interface[t] = next->interface;
        ++traces_at[next->interface];
        break;
      }
      current = next->next_block;
      came_through = next->interface;
      point = next->point;
      direction = next->direction;
    }
  }
  for (const auto& [interface, count] : traces_at) {
    const double share = static_cast<double>(count) / options.traces;
    flow.shares.push_back({interface, interfaces[interface].a, interfaces[interface].b, share});
    flow.lost -= count;
  }
  flow.seconds = seconds_since(start);
  return flow;
}

}  // namespace ashlar
