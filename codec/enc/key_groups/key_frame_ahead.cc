#include "codec/enc/key_groups/key_frame_ahead.h"

#include <memory>
#include <utility>

namespace meshvid {

KeyFrameAhead::KeyFrameAhead(const EncodeContext& ctx) : quiet_(WithoutProgress(ctx)) {}

KeyFrameAhead::~KeyFrameAhead() {
  for (auto& [frame, made] : made_) made.base.wait();
}

void KeyFrameAhead::Start(int frame, std::vector<TriangleMesh> views) {
  if (Started(frame)) return;
  auto proxy_made = std::make_shared<std::promise<StatusOr<FrameProxy>>>();
  InMaking& made = made_[frame];
  made.proxy = proxy_made->get_future();
  made.base = std::async(
      std::launch::async,
      [this, views = std::move(views), proxy_made]() -> StatusOr<TriangleMesh> {
        StatusOr<FrameProxy> proxy = BuildProxy(quiet_, views);
        if (!proxy.ok()) {
          const Status failed = proxy.status();
          proxy_made->set_value(std::move(proxy));
          return failed;
        }
        // The base's fit needs the frame's points alone (the target only for a user's base).
        FrameProxy points;
        points.points = proxy->points;
        points.normals = proxy->normals;
        proxy_made->set_value(std::move(proxy));
        return MakeKeyFrameBase(quiet_, views, points);
      });
}

std::optional<FrameProxy> KeyFrameAhead::TakeProxy(int frame) {
  const auto found = made_.find(frame);
  if (found == made_.end() || !found->second.proxy.valid()) return std::nullopt;
  StatusOr<FrameProxy> proxy = found->second.proxy.get();
  if (!proxy.ok()) return std::nullopt;
  return std::move(proxy).value();
}

std::optional<TriangleMesh> KeyFrameAhead::TakeBase(int frame) {
  while (!made_.empty() && made_.begin()->first < frame) {
    made_.begin()->second.base.wait();
    made_.erase(made_.begin());
  }
  const auto found = made_.find(frame);
  if (found == made_.end()) return std::nullopt;
  StatusOr<TriangleMesh> base = found->second.base.get();
  made_.erase(found);
  if (!base.ok()) return std::nullopt;
  return std::move(base).value();
}

}  // namespace meshvid
