#include "codec/enc/key_groups/tracking_targets.h"

#include <utility>

#include "codec/enc/key_groups/key_group_rules.h"

namespace meshvid {

TrackingTargets::TrackingTargets(const EncodeContext& ctx, ProxyCache* proxies)
    : ctx_(ctx), quiet_(WithoutProgress(ctx)), proxies_(*proxies) {}

TrackingTargets::~TrackingTargets() {
  // Waited for, as the thread refers to this object; what it made is not needed any more.
  if (in_making_) in_making_->made.wait();
}

TrackingTargets::Missing TrackingTargets::MissingOf(int t) const {
  return {.proxy = proxies_.count(t) == 0,
          .fused = ctx_.options.tuning.deform_track_fused && fused_.count(t) == 0};
}

StatusOr<TrackingTargets::Made> TrackingTargets::Make(const EncodeContext& ctx,
                                                      const std::vector<TriangleMesh>& views,
                                                      Missing missing) {
  Made made;
  if (missing.proxy) {
    MESHVID_ASSIGN_OR_RETURN(made.proxy, BuildProxy(ctx, views));
  }
  if (missing.fused) {
    FusedFrame& kept = made.fused.emplace();
    MESHVID_ASSIGN_OR_RETURN(kept.mesh,
                             FuseFrame(ctx, views, ctx.options.tuning.base_fusion_points));
    kept.normals = ComputeVertexNormals(kept.mesh);
  }
  return made;
}

void TrackingTargets::Keep(int t, Made made) {
  if (made.proxy && proxies_.count(t) == 0) proxies_[t] = *std::move(made.proxy);
  if (made.fused && fused_.count(t) == 0) fused_[t] = *std::move(made.fused);
}

void TrackingTargets::Collect(int t) {
  if (!in_making_ || in_making_->frame != t) return;
  std::future<StatusOr<Made>> making = std::move(in_making_->made);
  in_making_.reset();
  StatusOr<Made> made = making.get();
  if (made.ok()) Keep(t, *std::move(made));
}

Status TrackingTargets::StartMaking(int t) {
  const Missing missing = MissingOf(t);
  if (t < 0 || t >= ctx_.end || !missing.any()) return Status::Ok();
  if (in_making_) {
    if (in_making_->frame == t) return Status::Ok();
    Collect(in_making_->frame);  // another frame, kept before this one starts
  }
  // The views are loaded on this thread: the frame source is not made for several.
  MESHVID_ASSIGN_OR_RETURN(std::vector<TriangleMesh> views, ctx_.source.LoadFrame(t));
  std::future<StatusOr<Made>> made = std::async(
      std::launch::async,
      [this, views = std::move(views), missing] { return Make(quiet_, views, missing); });
  in_making_.emplace(InMaking{t, std::move(made)});
  return Status::Ok();
}

StatusOr<TrackingData> TrackingTargets::DataOf(int t) {
  Collect(t);
  if (const Missing missing = MissingOf(t); missing.any()) {
    // The frame's views, loaded once for whichever of the proxy and the fused target needs them.
    MESHVID_ASSIGN_OR_RETURN(const std::vector<TriangleMesh> views, ctx_.source.LoadFrame(t));
    MESHVID_ASSIGN_OR_RETURN(Made made, Make(ctx_, views, missing));
    Keep(t, std::move(made));
  }
  if (ctx_.options.tuning.deform_track_fused) {
    const FusedFrame& fused = fused_.at(t);
    return TrackingData{fused.mesh.positions, fused.normals};
  }
  const FrameProxy& proxy = proxies_.at(t);
  return TrackingData{proxy.points, proxy.normals};
}

const FusedFrame* TrackingTargets::Fused(int t) const {
  const auto found = fused_.find(t);
  return found != fused_.end() ? &found->second : nullptr;
}

void TrackingTargets::DropBefore(int t) {
  if (in_making_ && in_making_->frame < t) {
    in_making_->made.wait();
    in_making_.reset();
  }
  proxies_.erase(proxies_.begin(), proxies_.lower_bound(t));
  fused_.erase(fused_.begin(), fused_.lower_bound(t));
}

}  // namespace meshvid
