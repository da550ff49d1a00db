#include "codec/enc/segmentation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "codec/enc/rigid_step.h"

namespace meshvid {
namespace {

constexpr float kNoResidual = std::numeric_limits<float>::infinity();

/// Constant-velocity prediction of frame m from frames m-1 and m-2 (the warm start of a
/// grown window; the method copies frame m-1, which fast motion outruns).
RigidTransform Predict(const std::vector<RigidTransform>& transforms, int m) {
  if (m < 1) return RigidTransform{};
  if (m < 2) return transforms[m - 1];
  return PredictConstantVelocity(transforms[m - 2], transforms[m - 1]);
}

/// The base vertices and normals the segmentation poses.
struct BaseFrame {
  std::span<const Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
};

/// Correspondences of `members` under `transform`: the residual ||T v - c|| per member
/// (kNoResidual without a hit) and the hit points.
void Correspond(const BaseFrame& base, std::span<const std::uint32_t> members,
                const RigidTransform& transform, const ShootingTarget& target,
                const ShotLimits& limits, std::vector<float>* residuals,
                std::vector<Eigen::Vector3f>* hits, std::vector<Eigen::Vector3f>* normals) {
  residuals->resize(members.size());
  hits->resize(members.size());
  normals->resize(members.size());
  auto body = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t v = members[k];
      const Eigen::Vector3f origin = transform.Apply(base.positions[v]);
      const Eigen::Vector3f direction = transform.rotation * base.normals[v];
      const ShotHit hit = target.ShootHit(origin, direction, limits);
      if (std::isnan(hit.distance)) {
        (*residuals)[k] = kNoResidual;
      } else {
        (*hits)[k] = origin + hit.distance * direction;
        (*normals)[k] = hit.normal;
        (*residuals)[k] = std::abs(hit.distance);
      }
    }
  };
  if (members.size() < 256) {
    body(0, members.size());
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.size(), 128),
                      [&](const auto& r) { body(r.begin(), r.end()); });
  }
}

/// One Gauss-Newton step of eq. 5 for the pairs (T v_k, c_k), about their centroid (see
/// rigid_step.h). Returns the updated transform; `transform` unchanged if underdetermined.
RigidTransform RigidStep(const RigidTransform& transform, std::span<const Eigen::Vector3f> from,
                         std::span<const Eigen::Vector3f> to,
                         std::span<const Eigen::Vector3f> normals) {
  if (from.size() < 3) return transform;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> posed(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    posed[k] = transform.Apply(from[k]).cast<double>();
    centre += posed[k];
  }
  centre /= double(from.size());
  Matrix6d a = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  for (std::size_t k = 0; k < from.size(); ++k) {
    AddCorrespondence(posed[k] - centre, normals[k].cast<double>(),
                      posed[k] - to[k].cast<double>(), &a, &b);
  }
  DampRigidBlock(&a);
  const Vector6d x = a.ldlt().solve(-b);
  if (!x.allFinite()) return transform;
  return ApplyIncrement(transform, x, centre);
}

/// How many members agree within options.tolerance (eq. 6) and how many have data at all.
struct Agreement {
  std::size_t agree = 0;
  std::size_t seen = 0;
};

/// Eq. 5 and 6 for one frame: from `transform`, alternately finds correspondences and solves
/// the rigid transform on those within the tolerance. With `coarse`, the tolerance first
/// halves down from the whole search distance (motion between frames can exceed the
/// method's 3 x UserTol), then shrinks from `start_factor` x options.tolerance to
/// options.tolerance by options.tolerance_shrink. Returns the members' agreement with the
/// final transform.
Agreement Refine(const BaseFrame& base, std::span<const std::uint32_t> members,
                 const ShootingTarget& target, const SegmentationOptions& options,
                 float start_factor, bool coarse, RigidTransform* transform) {
  std::vector<float> residuals;
  std::vector<Eigen::Vector3f> hits, hit_normals, from, to, normals;
  const float fine_start = options.tolerance * std::max(1.0f, start_factor);
  float tol = fine_start;
  if (coarse) {
    while (tol * 2 < options.shot.max_distance) tol *= 2;
  }
  for (;;) {
    for (int it = 0; it < std::max(1, options.icp_iterations); ++it) {
      Correspond(base, members, *transform, target, options.shot, &residuals, &hits,
                 &hit_normals);
      from.clear();
      to.clear();
      normals.clear();
      for (std::size_t k = 0; k < members.size(); ++k) {
        if (residuals[k] < tol) {
          from.push_back(base.positions[members[k]]);
          to.push_back(hits[k]);
          normals.push_back(hit_normals[k]);
        }
      }
      if (from.size() < 3) break;
      *transform = RigidStep(*transform, from, to, normals);
    }
    if (tol <= options.tolerance) break;
    tol = tol > fine_start ? std::max(tol * 0.5f, fine_start)
                           : std::max(tol * options.tolerance_shrink, options.tolerance);
  }
  Correspond(base, members, *transform, target, options.shot, &residuals, &hits, &hit_normals);
  Agreement result;
  for (float r : residuals) {
    result.seen += std::isfinite(r);
    result.agree += r < options.tolerance;
  }
  return result;
}

/// Whether a solve is believable: enough members agree (at least 3 and a tenth of them),
/// most of the members that see data agree (a search that slid off the segment's surface
/// finds only a few stray agreements), no member moved farther from where `previous` (the
/// last frame's transform) put it than the search reaches (options.shot.max_distance), and
/// the segment turned by at most options.max_turn_per_frame.
bool Believable(const BaseFrame& base, std::span<const std::uint32_t> members,
                const SegmentationOptions& options, const Agreement& agreement,
                const RigidTransform& previous, const RigidTransform& solved) {
  if (agreement.agree < std::max<std::size_t>(3, members.size() / 10)) return false;
  if (2 * agreement.agree < agreement.seen) return false;
  for (std::uint32_t v : members) {
    const Eigen::Vector3f& p = base.positions[v];
    if ((solved.Apply(p) - previous.Apply(p)).norm() > options.shot.max_distance) return false;
  }
  // Small or flat segments leave a turn about their normal almost free; a body part does not
  // spin that fast between frames.
  const float turn = solved.rotation.angularDistance(previous.rotation);
  return turn <= options.max_turn_per_frame;
}

/// Solves one frame's transform of a segment from the prediction `*transform` (`previous`: the
/// last frame's, see Believable): a fine search (from start_factor x the tolerance) and a
/// coarse one (from the whole search distance) both run, and the believable one more members
/// agree with wins. Returns its agreement; nothing, leaving `*transform` as it was, when
/// neither is believable (e.g. the segment is unseen).
std::optional<Agreement> SolveFrame(const BaseFrame& base, std::span<const std::uint32_t> members,
                                    const ShootingTarget& target,
                                    const SegmentationOptions& options, float start_factor,
                                    const RigidTransform& previous, RigidTransform* transform) {
  RigidTransform fine = *transform, coarse = *transform;
  const Agreement fine_agreement =
      Refine(base, members, target, options, start_factor, /*coarse=*/false, &fine);
  const Agreement coarse_agreement =
      Refine(base, members, target, options, start_factor, /*coarse=*/true, &coarse);
  const bool fine_ok = Believable(base, members, options, fine_agreement, previous, fine);
  const bool coarse_ok = Believable(base, members, options, coarse_agreement, previous, coarse);
  if (!fine_ok && !coarse_ok) return std::nullopt;
  if (coarse_ok && (!fine_ok || coarse_agreement.agree > fine_agreement.agree)) {
    *transform = coarse;
    return coarse_agreement;
  }
  *transform = fine;
  return fine_agreement;
}

/// The largest connected piece of the vertices flagged in `member` (flags of the others are
/// cleared); returns its vertices.
std::vector<std::uint32_t> KeepLargestPiece(
    const std::vector<std::vector<std::uint32_t>>& neighbours, std::vector<char>* member) {
  const std::size_t n = member->size();
  std::vector<std::int32_t> piece(n, -1);
  std::vector<std::uint32_t> stack, best;
  std::int32_t pieces = 0;
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (!(*member)[seed] || piece[seed] >= 0) continue;
    std::vector<std::uint32_t> current;
    stack.assign(1, seed);
    piece[seed] = pieces;
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      current.push_back(v);
      for (std::uint32_t w : neighbours[v]) {
        if ((*member)[w] && piece[w] < 0) {
          piece[w] = pieces;
          stack.push_back(w);
        }
      }
    }
    if (current.size() > best.size()) best.swap(current);
    ++pieces;
  }
  std::fill(member->begin(), member->end(), 0);
  for (std::uint32_t v : best) (*member)[v] = 1;
  std::sort(best.begin(), best.end());
  return best;
}


/// Breadth-first hop counts from `sources` over the mesh (-1: unreachable).
std::vector<std::int32_t> Hops(const std::vector<std::vector<std::uint32_t>>& neighbours,
                               std::vector<std::uint32_t> sources) {
  std::vector<std::int32_t> hops(neighbours.size(), -1);
  for (std::uint32_t v : sources) hops[v] = 0;
  for (std::size_t head = 0; head < sources.size(); ++head) {
    const std::uint32_t v = sources[head];
    for (std::uint32_t w : neighbours[v]) {
      if (hops[w] >= 0) continue;
      hops[w] = hops[v] + 1;
      sources.push_back(w);
    }
  }
  return hops;
}

/// What every stage of one segmentation shares.
struct SegmentContext {
  BaseFrame base;
  std::vector<std::vector<std::uint32_t>> neighbours;
  FrameTargets targets;
  const SegmentationOptions& options;
  /// The track of the segment nearest the one being found (its parent), or null for the
  /// first: a segment that is not seen in a frame moves with its parent.
  const std::vector<RigidTransform>* parent = nullptr;
};

/// Frame m's transform of a segment that cannot be solved there: its frame m-1 transform,
/// carried by the parent's motion from m-1 to m when there is a parent.
RigidTransform Carried(const SegmentContext& context, const std::vector<RigidTransform>& own,
                       int m) {
  if (m < 1) return RigidTransform{};
  if (context.parent == nullptr) return own[m - 1];
  const std::vector<RigidTransform>& parent = *context.parent;
  return Compose(Compose(parent[m], Inverse(parent[m - 1])), own[m - 1]);
}

/// The prediction a frame's solve starts from: carried by the parent if there is one (a limb
/// moves with the body), else constant velocity.
RigidTransform PredictSegment(const SegmentContext& context,
                              const std::vector<RigidTransform>& own, int m) {
  return context.parent != nullptr ? Carried(context, own, m) : Predict(own, m);
}

/// The segment whose vertex is fewest mesh hops from `seed`; -1 if no vertex is labelled.
std::int32_t NearestSegment(const std::vector<std::vector<std::uint32_t>>& neighbours,
                            const std::vector<std::int32_t>& labels, std::uint32_t seed) {
  const std::vector<std::int32_t> hops = Hops(neighbours, {seed});
  std::int32_t best = -1;
  for (std::uint32_t v = 0; v < labels.size(); ++v) {
    if (labels[v] >= 0 && hops[v] >= 0 && (best < 0 || hops[v] < hops[best])) best = v;
  }
  return best < 0 ? -1 : labels[best];
}

/// Without seed_vertices, a seed patch holds this fraction (1/divisor) of the base.
constexpr std::size_t kAutoSeedDivisor = 40;
/// Seeds tried per segment allowed before the segmentation gives up.
constexpr int kAttemptsPerSegment = 3;
/// Most rounds of growth (score every unsegmented vertex, solve again) per segment.
constexpr int kGrowRounds = 16;

/// The seedable, unsegmented vertex farthest (in mesh hops) from every segmented or
/// unseedable one: the middle of the largest region still free. -1 if none is left.
std::int64_t PickSeed(const std::vector<std::vector<std::uint32_t>>& neighbours,
                      const std::vector<char>& unsegmented, const std::vector<char>& seedable) {
  const std::size_t n = unsegmented.size();
  auto is_free = [&](std::uint32_t v) { return unsegmented[v] && seedable[v]; };
  std::vector<std::uint32_t> blockers;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (!is_free(v)) blockers.push_back(v);
  }
  auto farthest = [&](const std::vector<std::int32_t>& hops) {
    std::int64_t best = -1;
    for (std::uint32_t v = 0; v < n; ++v) {
      if (is_free(v) && hops[v] >= 0 && (best < 0 || hops[v] > hops[best])) best = v;
    }
    return best;
  };
  if (!blockers.empty()) {
    const std::int64_t best = farthest(Hops(neighbours, blockers));
    if (best >= 0) return best;
    // The free vertices left are not connected to any blocker: take any.
    for (std::uint32_t v = 0; v < n; ++v) {
      if (is_free(v)) return v;
    }
    return -1;
  }
  if (n == 0) return -1;
  // Nothing blocks yet (every vertex seen): the middle of a longest hop path, i.e. the
  // vertex most hops from both ends of it.
  const std::int64_t a = farthest(Hops(neighbours, {0}));
  const auto from_a = Hops(neighbours, {std::uint32_t(a)});
  const std::int64_t b = farthest(from_a);
  const auto from_b = Hops(neighbours, {std::uint32_t(b)});
  std::int64_t best = a;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (from_a[v] >= 0 && from_b[v] >= 0 &&
        std::min(from_a[v], from_b[v]) > std::min(from_a[best], from_b[best])) {
      best = v;
    }
  }
  return best;
}

/// Breadth-first patch of up to `size` unsegmented vertices around `seed`.
std::vector<std::uint32_t> GrowPatch(const std::vector<std::vector<std::uint32_t>>& neighbours,
                                     const std::vector<char>& unsegmented, std::uint32_t seed,
                                     std::size_t size) {
  std::vector<std::uint32_t> patch{seed};
  std::vector<char> taken(unsegmented.size(), 0);
  taken[seed] = 1;
  for (std::size_t head = 0; head < patch.size() && patch.size() < size; ++head) {
    for (std::uint32_t w : neighbours[patch[head]]) {
      if (taken[w] || !unsegmented[w]) continue;
      taken[w] = 1;
      patch.push_back(w);
      if (patch.size() >= size) break;
    }
  }
  std::sort(patch.begin(), patch.end());
  return patch;
}

/// Follows a seed patch through the frames in order (eq. 5 and 6 over a growing window,
/// warm-started by PredictSegment): members whose data disagrees in more than
/// options.occlusion_frames frames, or never agrees, leave; the largest connected piece is
/// kept. Returns the surviving members (fewer than 3: the patch could not be followed).
std::vector<std::uint32_t> TrackPatch(const SegmentContext& context,
                                      std::vector<std::uint32_t> members,
                                      std::vector<RigidTransform>* track) {
  const SegmentationOptions& options = context.options;
  const std::size_t n = context.base.positions.size();
  const int frames = static_cast<int>(context.targets.size());
  std::vector<char> member(n, 0);
  for (std::uint32_t v : members) member[v] = 1;
  std::vector<int> failures(n, 0), successes(n, 0);
  std::vector<char> agreeing(n, 1);
  std::vector<std::uint32_t> solvers;
  std::vector<float> residuals;
  std::vector<Eigen::Vector3f> hits, hit_normals;
  track->assign(frames, RigidTransform{});
  for (int m = 0; m < frames && members.size() >= 3; ++m) {
    (*track)[m] = PredictSegment(context, *track, m);
    const ShootingTarget* target = context.targets[m];
    if (target == nullptr) continue;
    // Solve on the members that agreed when last seen: a piece that has parted from the
    // segment's motion no longer pulls the solution, even before it is dropped.
    solvers.clear();
    for (std::uint32_t v : members) {
      if (agreeing[v]) solvers.push_back(v);
    }
    if (solvers.size() < 3) solvers = members;
    // The base is fitted to frame 0: its transform stays the identity (a search there can
    // only slide a small patch along the surface). An unsolved segment is carried.
    if (m > 0 && !SolveFrame(context.base, solvers, *target, options,
                             options.initial_tolerance_factor, (*track)[m - 1], &(*track)[m])) {
      (*track)[m] = Carried(context, *track, m);
    }
    Correspond(context.base, members, (*track)[m], *target, options.shot, &residuals, &hits,
               &hit_normals);
    for (std::size_t k = 0; k < members.size(); ++k) {
      const std::uint32_t v = members[k];
      // A miss is an occlusion and costs nothing; a hit outside the tolerance disagrees.
      if (!std::isfinite(residuals[k])) continue;
      const bool agrees = residuals[k] < options.tolerance;
      ++(agrees ? successes : failures)[v];
      agreeing[v] = agrees;
    }
    const bool last = m + 1 == frames;
    for (std::uint32_t v : members) {
      if (failures[v] > options.occlusion_frames || (last && successes[v] == 0)) member[v] = 0;
    }
    members = KeepLargestPiece(context.neighbours, &member);
  }
  return members;
}

/// Eq. 5 once more on a segment's final members, frame after frame from frame 0's identity:
/// each frame is solved from both the growth's track and PredictSegment's prediction (the
/// more members agree, the better), and is Carried where neither solve is believable.
/// Returns the number of frames solved.
int FollowSegment(const SegmentContext& context, std::span<const std::uint32_t> members,
                  std::vector<RigidTransform>* track) {
  int solved = 0;
  const int frames = static_cast<int>(context.targets.size());
  std::vector<RigidTransform> followed(frames);
  for (int m = 1; m < frames; ++m) {
    const RigidTransform previous = followed[m - 1];
    followed[m] = PredictSegment(context, followed, m);
    const ShootingTarget* target = context.targets[m];
    if (target == nullptr) continue;
    // Where the growth's track is better than the prediction (it saw more), start there.
    RigidTransform from_track = (*track)[m];
    const std::optional<Agreement> tracked = SolveFrame(context.base, members, *target,
                                                        context.options, 1.0f, previous,
                                                        &from_track);
    RigidTransform from_prediction = followed[m];
    const std::optional<Agreement> predicted =
        SolveFrame(context.base, members, *target, context.options,
                   context.options.initial_tolerance_factor, previous, &from_prediction);
    if (!tracked && !predicted) {
      followed[m] = Carried(context, followed, m);
      continue;
    }
    ++solved;
    followed[m] = !predicted || (tracked && tracked->agree >= predicted->agree)
                      ? from_track
                      : from_prediction;
  }
  *track = std::move(followed);
  return solved;
}

/// Grows a tracked segment by the method's tolerance schedule: every unsegmented vertex whose
/// data agrees with the segment's track within the current tolerance (eq. 6 failing in at most
/// options.occlusion_frames frames, holding in at least one) joins, the largest connected piece
/// is kept and eq. 5 is solved again on it; the tolerance starts at
/// options.initial_tolerance_factor x options.tolerance and shrinks by
/// options.tolerance_shrink, then rounds at the tolerance go on until the members settle.
/// Returns the final members; `track` holds their transforms.
std::vector<std::uint32_t> GrowSegment(const SegmentContext& context,
                                       const std::vector<char>& unsegmented,
                                       std::vector<std::uint32_t> members,
                                       std::vector<RigidTransform>* track) {
  const SegmentationOptions& options = context.options;
  const std::size_t n = context.base.positions.size();
  const int frames = static_cast<int>(context.targets.size());
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (unsegmented[v]) candidates.push_back(v);
  }
  std::vector<float> residuals;
  std::vector<Eigen::Vector3f> hits, hit_normals;
  float tol = options.tolerance * std::max(1.0f, options.initial_tolerance_factor);
  for (int round = 0; round < kGrowRounds; ++round) {
    std::vector<int> failures(candidates.size(), 0), successes(candidates.size(), 0);
    for (int m = 0; m < frames; ++m) {
      if (context.targets[m] == nullptr) continue;
      Correspond(context.base, candidates, (*track)[m], *context.targets[m], options.shot,
                 &residuals, &hits, &hit_normals);
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (!std::isfinite(residuals[k])) continue;
        ++(residuals[k] < tol ? successes : failures)[k];
      }
    }
    std::vector<char> member(n, 0);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      member[candidates[k]] = failures[k] <= options.occlusion_frames && successes[k] > 0 &&
                              successes[k] >= failures[k];
    }
    std::vector<std::uint32_t> grown = KeepLargestPiece(context.neighbours, &member);
    if (grown.size() < 3) return grown;
    const bool settled = tol <= options.tolerance && grown == members;
    members = std::move(grown);
    // Eq. 5 again on the new members, from the current track (frame 0 stays the identity).
    for (int m = 1; m < frames; ++m) {
      if (context.targets[m] == nullptr) continue;
      RigidTransform refined = (*track)[m];
      const Agreement agreement = Refine(context.base, members, *context.targets[m], options,
                                         tol / options.tolerance, /*coarse=*/false, &refined);
      if (Believable(context.base, members, options, agreement, (*track)[m - 1], refined)) {
        (*track)[m] = refined;
      }
    }
    if (settled) break;
    tol = std::max(options.tolerance, tol * options.tolerance_shrink);
  }
  return members;
}

}  // namespace

StatusOr<Segmentation> SegmentPiecewiseRigid(const BaseTopology& topology,
                                             FrameTargets targets,
                                             const SegmentationOptions& options,
                                             const ProgressCallback& progress) {
  const TriangleMesh& base = topology.mesh;
  MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "base mesh"));
  if (targets.empty()) return InvalidArgumentError("segmentation needs at least one frame");
  if (!(options.tolerance > 0)) return InvalidArgumentError("the tolerance must be positive");
  if (!(options.tolerance_shrink > 0 && options.tolerance_shrink < 1)) {
    return InvalidArgumentError("the tolerance shrink factor must be in (0, 1)");
  }
  const std::size_t n = base.vertex_count();
  const int min_size = std::max(3, options.min_segment_vertices);
  const std::size_t seed_size =
      options.seed_vertices > 0
          ? std::size_t(options.seed_vertices)
          : std::max<std::size_t>(std::size_t(3 * min_size), n / kAutoSeedDivisor);
  SegmentContext context{BaseFrame{base.positions, topology.normals}, topology.neighbours,
                         targets, options};
  std::vector<std::vector<RigidTransform>> segment_tracks;
  const int frames_with_data = static_cast<int>(
      std::count_if(targets.begin(), targets.end(), [](const auto* t) { return t != nullptr; }));

  // Seeds must be seen in frame 0, where the base is fitted to the data.
  std::vector<char> seedable(n, 0);
  {
    std::vector<std::uint32_t> all(n);
    for (std::uint32_t v = 0; v < n; ++v) all[v] = v;
    std::vector<float> residuals;
    std::vector<Eigen::Vector3f> hits, normals;
    const ShootingTarget* first = nullptr;
    for (const ShootingTarget* target : targets) {
      if (target != nullptr) {
        first = target;
        break;
      }
    }
    if (first == nullptr) return InvalidArgumentError("segmentation needs a frame with data");
    Correspond(context.base, all, RigidTransform{}, *first, options.shot, &residuals, &hits,
               &normals);
    for (std::uint32_t v = 0; v < n; ++v) seedable[v] = residuals[v] < options.tolerance;
  }

  Segmentation result;
  result.labels.assign(n, kUnregistered);
  result.transforms.assign(targets.size(), {});
  std::vector<char> unsegmented(n, 1);
  std::size_t remaining = n;
  int attempts = 0;
  while (result.segment_count < options.max_segments && remaining >= std::size_t(min_size) &&
         attempts < kAttemptsPerSegment * options.max_segments) {
    if (!ReportProgress(progress, "segmentation", long(n - remaining), long(n))) {
      return CancelledError("segmentation cancelled");
    }
    const std::int64_t seed = PickSeed(context.neighbours, unsegmented, seedable);
    if (seed < 0) break;
    ++attempts;
    // However the attempt ends, this region no longer seeds: the next attempt starts
    // elsewhere.
    std::vector<std::uint32_t> patch =
        GrowPatch(context.neighbours, unsegmented, std::uint32_t(seed), seed_size);
    for (std::uint32_t v : patch) seedable[v] = 0;
    if (patch.size() < std::size_t(min_size)) continue;
    const std::int32_t parent =
        NearestSegment(context.neighbours, result.labels, std::uint32_t(seed));
    context.parent = parent >= 0 ? &segment_tracks[parent] : nullptr;
    std::vector<RigidTransform> track;
    std::vector<std::uint32_t> members = TrackPatch(context, patch, &track);
    // Grow on the patch's track, follow the grown segment through the frames again, then
    // grow and follow once more from that better track.
    int solved_frames = 0;
    for (int pass = 0; pass < 2 && members.size() >= std::size_t(min_size); ++pass) {
      members = GrowSegment(context, unsegmented, std::move(members), &track);
      if (members.size() >= std::size_t(min_size)) {
        solved_frames = FollowSegment(context, members, &track);
      }
    }
    if (members.size() < std::size_t(min_size)) continue;
    // A segment that cannot be solved in too many frames has lost its data (a limb that
    // left the search range while unseen): its vertices are better interpolated.
    if (solved_frames < options.min_solved_share * float(frames_with_data - 1)) {
      for (std::uint32_t v : members) seedable[v] = 0;
      continue;
    }
    for (std::uint32_t v : members) {
      result.labels[v] = result.segment_count;
      unsegmented[v] = 0;
      seedable[v] = 0;
    }
    remaining -= members.size();
    for (std::size_t m = 0; m < targets.size(); ++m) result.transforms[m].push_back(track[m]);
    segment_tracks.push_back(track);
    ++result.segment_count;
  }
  return result;
}

std::vector<RigidTransform> TrackSegments(const BaseTopology& base,
                                          std::span<const std::int32_t> labels,
                                          int segment_count, const ShootingTarget& target,
                                          std::span<const RigidTransform> initial,
                                          const SegmentationOptions& options) {
  BaseFrame frame{base.mesh.positions, base.normals};
  std::vector<std::vector<std::uint32_t>> members(segment_count);
  for (std::uint32_t v = 0; v < labels.size(); ++v) {
    if (labels[v] >= 0 && labels[v] < segment_count) members[labels[v]].push_back(v);
  }
  std::vector<RigidTransform> result(initial.begin(), initial.end());
  result.resize(segment_count);
  for (int s = 0; s < segment_count; ++s) {
    if (members[s].size() < 3) continue;
    SolveFrame(frame, members[s], target, options, options.initial_tolerance_factor, initial[s],
               &result[s]);
  }
  return result;
}

int SolveSegment(const BaseTopology& base, std::span<const std::uint32_t> members,
                 const ShootingTarget& target, const SegmentationOptions& options,
                 RigidTransform* transform) {
  if (members.size() < 3) return -1;
  const BaseFrame frame{base.mesh.positions, base.normals};
  const RigidTransform start = *transform;
  const std::optional<Agreement> agreement = SolveFrame(
      frame, members, target, options, options.initial_tolerance_factor, start, transform);
  return agreement ? static_cast<int>(agreement->agree) : -1;
}

}  // namespace meshvid
