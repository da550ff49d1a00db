// The WebAssembly side of meshvid's browser decoder: the container, the key groups' geometry
// and the reconstruction of frames, in the same code as the native decoder (format/,
// codec/common, codec/dec). What the browser does better stays in JavaScript
// (web/decoder/meshvid.mjs): the Draco base meshes (draco3d), zstd (fzstd) and the video
// (WebCodecs). Calls return "" or an error's text; views into the module's memory stay valid
// until the next call.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "codec/dec/gof_side_info.h"
#include "codec/dec/key_group_geometry.h"
#include "codec/dec/stream_header.h"
#include "format/container_reader.h"
#include "web/wasm/fetched_ranges.h"

namespace meshvid {
namespace {

using emscripten::val;

/// One group of frames as the page decodes it: its side information, and its pictures, which
/// the page writes (pictureAddress) from the video decoder's output.
struct WebGroup {
  std::uint32_t first_frame = 0;
  GofSideInfo side;
  const DisplacementLayout* layout = nullptr;
  std::vector<GreyPicture> pictures;
};

/// A .mvid opened from bytes in the module's memory, or streamed: read through range requests
/// as the page fetches them.
class WasmDecoder {
 public:
  /// Opens `bytes` (a Uint8Array, copied); a file cut short of its header's frame count is
  /// refused unless `allow_partial`. `name` names the file in errors.
  std::string Open(std::string bytes, std::string name, bool allow_partial) {
    reader_.reset();
    ranges_.reset();
    return Adopt(
        ContainerReader::OpenMemory(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), name),
        allow_partial);
  }

  /// Starts a file of `size` bytes streamed by range requests: the page adds what arrives
  /// (AddBytes) and fetches what a call found missing (TakeMissing), then calls again.
  void BeginStream(double size, std::string name) {
    reader_.reset();
    ranges_ = std::make_unique<FetchedRanges>(static_cast<std::uint64_t>(size), std::move(name));
  }
  /// Holds `bytes` (a Uint8Array) as the streamed file's bytes from `offset`.
  void AddBytes(double offset, val bytes) {
    ranges_->Add(static_cast<std::uint64_t>(offset),
                 emscripten::convertJSArrayToNumberVector<std::uint8_t>(bytes));
  }
  /// The first range {start, end} of [start, end) of the streamed file that has not arrived,
  /// or null.
  val FirstGap(double start, double end) const {
    if (!ranges_ || end <= start) return val::null();
    return Range(ranges_->FirstGap(static_cast<std::uint64_t>(start),
                                   static_cast<std::uint64_t>(end - start)));
  }
  /// The first range {start, end} a call since the last TakeMissing needed and did not have
  /// (its error is then only that), or null.
  val TakeMissing() { return ranges_ ? Range(ranges_->TakeMissing()) : val::null(); }
  /// Opens the streamed file from the bytes that have arrived (its start and its end, where
  /// the index is); as Open otherwise.
  std::string OpenStream(bool allow_partial) {
    return Adopt(ContainerReader::Open(std::make_unique<BorrowedRanges>(*ranges_)), allow_partial);
  }

  /// The bytes {start, end} of group `g`'s chunk.
  val GroupSpan(int g) {
    const std::uint64_t start = reader_->gofs()[g].offset;
    return Span(start, ChunkEnd(start));
  }
  /// The bytes {start, end} of key group `k`'s BASE and MOTN chunks ({0, 0} if it has none).
  val KeyGroupSpan(int k) {
    const KeyGroupEntry& key_group = reader_->key_groups()[k];
    std::uint64_t start = UINT64_MAX, last = 0;
    for (std::uint64_t offset : {key_group.base_offset, key_group.motion_offset}) {
      if (offset == 0) continue;
      start = std::min(start, offset);
      last = std::max(last, offset);
    }
    return start == UINT64_MAX ? Span(0, 0) : Span(start, ChunkEnd(last));
  }

  /// True once a file is open.
  bool IsOpen() const { return reader_.has_value(); }
  int FrameCount() const { return static_cast<int>(reader_->frame_count()); }
  int DeclaredFrameCount() const { return static_cast<int>(reader_->header().frame_count); }
  double FrameRate() const {
    return double(reader_->header().frame_rate_numerator) /
           reader_->header().frame_rate_denominator;
  }
  int Levels() const { return static_cast<int>(reader_->header().level_count); }
  int GofCount() const { return static_cast<int>(reader_->gof_count()); }
  int KeyGroupCount() const { return static_cast<int>(reader_->key_groups().size()); }
  std::string CodecTag() const { return reader_->header().streams[0].codec; }
  std::string MetadataJson() const { return reader_->header().metadata_json; }
  /// The group holding frame `t`, or -1.
  int GofOfFrame(int t) const {
    if (t < 0) return -1;
    StatusOr<std::size_t> gof = reader_->FindGof(static_cast<std::uint64_t>(t));
    return gof.ok() ? static_cast<int>(*gof) : -1;
  }
  int KeyGroupOfGof(int g) const { return static_cast<int>(reader_->KeyGroupOfGof(g)); }
  int GofFirstFrame(int g) const { return static_cast<int>(reader_->gofs()[g].first_frame); }
  int GofFrameCount(int g) const { return static_cast<int>(reader_->gofs()[g].frame_count); }

  /// Key group `k`'s BASE payload (Draco), or an empty view with Error() set.
  val BaseBytes(int k) {
    error_.clear();
    StatusOr<std::vector<std::uint8_t>> base = reader_->ReadBase(k);
    if (!base.ok()) {
      error_ = base.status().ToString();
      bytes_.clear();
    } else {
      bytes_ = std::move(*base);
    }
    return val(emscripten::typed_memory_view(bytes_.size(), bytes_.data()));
  }

  /// Makes key group `k` current from its base mesh as Draco decoded it (positions: Float32Array
  /// of x y z, triangles: Uint32Array of corner indices) and its MOTN payload.
  std::string SetKeyGroup(int k, val positions, val triangles) {
    StatusOr<KeyGroupGeometry> geometry = BuildGeometry(k, positions, triangles);
    if (!geometry.ok()) return geometry.status().ToString();
    MakeCurrent(k, std::move(*geometry));
    return "";
  }
  /// Builds key group `k`'s geometry as SetKeyGroup does, with its triangles at `level`, without
  /// making it current: the next key group, made while the current one plays.
  std::string PrepareKeyGroup(int k, val positions, val triangles, int level) {
    StatusOr<KeyGroupGeometry> geometry = BuildGeometry(k, positions, triangles);
    if (!geometry.ok()) return geometry.status().ToString();
    if (level >= 0 && level <= Levels()) geometry->Triangles(level);
    prepared_.emplace(std::move(*geometry));
    prepared_key_group_ = k;
    return "";
  }
  /// The key group PrepareKeyGroup made ready, or -1.
  int PreparedKeyGroup() const { return prepared_ ? prepared_key_group_ : -1; }
  /// Makes key group `k` current from PrepareKeyGroup's work; false when it was not prepared.
  bool UsePreparedKeyGroup(int k) {
    if (!prepared_ || prepared_key_group_ != k) return false;
    MakeCurrent(k, std::move(*prepared_));
    prepared_.reset();
    return true;
  }
  int CurrentKeyGroup() const { return geometry_ ? key_group_ : -1; }

  /// Reads group `g` and decodes its side information; its key group must be current.
  std::string LoadGof(int g) {
    group_.reset();
    StatusOr<GroupOfFrames> gof = ReadGof(g);
    if (!gof.ok()) return gof.status().ToString();
    StatusOr<WebGroup> group = GroupOf(*gof);
    if (!group.ok()) return group.status().ToString();
    for (GreyPicture& picture : group->pictures) {
      picture.width = group->layout->width();
      picture.height = group->layout->height();
      picture.samples.assign(std::size_t(picture.width) * picture.height, 0);
    }
    group_.emplace(std::move(*group));
    return "";
  }

  /// Group `g`'s video as its decoder needs it, without making it the loaded group (so the
  /// page can decode the next group while it shows this one): {packets: [Uint8Array] in
  /// decoding order, config: Uint8Array (the decoder configuration record), width, height
  /// (0 until the group's key group is loaded)}, or {error}.
  val GroupVideo(int g) {
    val video = val::object();
    const auto fail = [&video](const Status& status) {
      video.set("error", status.ToString());
      return video;
    };
    if (g < 0 || g >= GofCount())
      return fail(InvalidArgumentError("no group " + std::to_string(g)));
    StatusOr<GroupOfFrames> gof = reader_->ReadGof(g);
    if (!gof.ok()) return fail(gof.status());
    StatusOr<GofVideoHead> head = ReadGofVideoHead(gof->transforms);
    if (!head.ok()) return fail(head.status().WithContext(Name() + ": group " + std::to_string(g)));
    int width = 0, height = 0;
    if (geometry_ && KeyGroupOfGof(g) == key_group_) {
      StatusOr<const DisplacementLayout*> layout = LayoutOf(head->packing);
      if (!layout.ok()) {
        return fail(layout.status().WithContext(Name() + ": group " + std::to_string(g)));
      }
      width = (*layout)->width();
      height = (*layout)->height();
    }
    val packets = val::array();
    for (const std::vector<std::uint8_t>& packet : gof->packets[0]) {
      packets.call<void>("push", Copy(packet));
    }
    video.set("packets", packets);
    video.set("config", Copy(head->video_config));
    video.set("width", width);
    video.set("height", height);
    return video;
  }

  /// Samples in each picture of the loaded group.
  int PictureSamples() const { return group_->layout->width() * group_->layout->height(); }
  /// Where the page writes picture `i` (presentation order) of the loaded group: width x height
  /// 16-bit samples, row by row.
  std::uintptr_t PictureAddress(int i) {
    return reinterpret_cast<std::uintptr_t>(group_->pictures[i].samples.data());
  }

  /// Reconstructs frame `t` at `level` from the loaded group's pictures (Positions()).
  std::string DecodePositions(int t, int level) {
    if (level < 0 || level > Levels()) {
      return "invalid argument: level " + std::to_string(level) + " is not in 0.." +
             std::to_string(Levels());
    }
    if (!group_ || t < int(group_->first_frame) ||
        t >= int(group_->first_frame + group_->pictures.size())) {
      return "invalid argument: frame " + std::to_string(t) + "'s group is not loaded";
    }
    const std::size_t local = t - group_->first_frame;
    geometry_->Positions(group_->side.transforms[local], group_->pictures[local], *group_->layout,
                         group_->side.displacement_range, level, &positions_);
    return "";
  }
  /// The last decoded positions: x y z per vertex.
  val Positions() const {
    return val(emscripten::typed_memory_view(3 * positions_.size(),
                                             reinterpret_cast<const float*>(positions_.data())));
  }
  /// The current key group's triangles at `level` (the same at every frame of it).
  val Triangles(int level) {
    if (!geometry_ || level < 0 || level > Levels()) {
      return val(emscripten::typed_memory_view(0, static_cast<const std::uint32_t*>(nullptr)));
    }
    const std::vector<Triangle>& triangles = geometry_->Triangles(level);
    static_assert(sizeof(Triangle) == 3 * sizeof(std::uint32_t));
    return val(emscripten::typed_memory_view(
        3 * triangles.size(), reinterpret_cast<const std::uint32_t*>(triangles.data())));
  }
  /// The error of the last call that returns a view ("" if none).
  std::string Error() const { return error_; }

 private:
  /// Makes `reader` the file's, refusing one with no readable frame, or (unless
  /// `allow_partial`) fewer than its header promises.
  std::string Adopt(StatusOr<ContainerReader> reader, bool allow_partial) {
    reader_.reset();
    geometry_.reset();
    prepared_.reset();
    group_.reset();
    key_group_ = -1;
    if (!reader.ok()) return reader.status().ToString();
    const std::string& name = reader->source().name();
    StatusOr<VideoCodec> codec = CheckStreamHeader(reader->header(), name);
    if (!codec.ok()) return codec.status().ToString();
    const Status readable = CheckReadableFrames(reader->frame_count(), reader->header().frame_count,
                                                allow_partial, name, "allowPartial");
    if (!readable.ok()) return readable.ToString();
    reader_.emplace(std::move(*reader));
    return "";
  }

  /// Key group `k`'s geometry from its decoded base mesh (see SetKeyGroup) and MOTN payload.
  StatusOr<KeyGroupGeometry> BuildGeometry(int k, val positions, val triangles) {
    const std::string context = Name() + ": key group " + std::to_string(k);
    const std::vector<float> xyz = emscripten::convertJSArrayToNumberVector<float>(positions);
    const std::vector<std::uint32_t> corners =
        emscripten::convertJSArrayToNumberVector<std::uint32_t>(triangles);
    if (xyz.size() % 3 != 0 || corners.size() % 3 != 0) {
      return CorruptError(context + " BASE: not whole vertices and triangles");
    }
    TriangleMesh base;
    base.positions.resize(xyz.size() / 3);
    for (std::size_t v = 0; v < base.positions.size(); ++v) {
      base.positions[v] = Eigen::Vector3f(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    }
    base.triangles.resize(corners.size() / 3);
    for (std::size_t t = 0; t < base.triangles.size(); ++t) {
      base.triangles[t] = Triangle(corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]);
    }
    MESHVID_RETURN_IF_ERROR(ValidateMesh(base, "base mesh").WithContext(context + " BASE"));
    StatusOr<std::vector<std::uint8_t>> motion = reader_->ReadMotion(k);
    if (!motion.ok()) return motion.status().WithContext(context);
    StatusOr<KeyGroupGeometry> geometry =
        KeyGroupGeometry::Create(std::move(base), *motion, Levels());
    if (!geometry.ok()) return geometry.status().WithContext(context + " MOTN");
    return geometry;
  }

  void MakeCurrent(int k, KeyGroupGeometry geometry) {
    group_.reset();
    geometry_.emplace(std::move(geometry));
    key_group_ = k;
  }

  /// Where the chunk at `offset` ends: where the next chunk the index knows of starts, or
  /// the file does (the index and trailer follow the last group).
  std::uint64_t ChunkEnd(std::uint64_t offset) {
    std::uint64_t end = reader_->source().size();
    const auto consider = [&](std::uint64_t next) {
      if (next > offset) end = std::min(end, next);
    };
    for (const IndexEntry& gof : reader_->gofs()) consider(gof.offset);
    for (const KeyGroupEntry& key_group : reader_->key_groups()) {
      consider(key_group.base_offset);
      consider(key_group.motion_offset);
    }
    return end;
  }

  static val Span(std::uint64_t start, std::uint64_t end) {
    val span = val::object();
    span.set("start", double(start));
    span.set("end", double(end));
    return span;
  }

  /// The file's name in errors.
  const std::string& Name() { return reader_->source().name(); }

  /// {start, end} of `range`, or null.
  static val Range(const std::optional<std::pair<std::uint64_t, std::uint64_t>>& range) {
    return range ? Span(range->first, range->second) : val::null();
  }

  /// Group `g` (kInvalidArgument when there is none or its key group is not current).
  StatusOr<GroupOfFrames> ReadGof(int g) {
    if (g < 0 || g >= GofCount()) return InvalidArgumentError("no group " + std::to_string(g));
    if (!geometry_ || KeyGroupOfGof(g) != key_group_) {
      return InvalidArgumentError(Name() + ": group " + std::to_string(g) +
                                  ": its key group is not loaded");
    }
    return reader_->ReadGof(g);
  }

  /// `gof` with its side information decoded and one empty picture per frame.
  StatusOr<WebGroup> GroupOf(const GroupOfFrames& gof) {
    const std::string context = Name() + ": group " + std::to_string(gof.gof_index);
    WebGroup group;
    group.first_frame = gof.first_frame;
    StatusOr<GofSideInfo> side =
        DecodeGofSideInfo(gof.transforms, gof.frame_count, geometry_->motion().segment_count,
                          geometry_->quantization());
    if (!side.ok()) return side.status().WithContext(context);
    group.side = std::move(*side);
    StatusOr<const DisplacementLayout*> layout = LayoutOf(group.side.packing);
    if (!layout.ok()) return layout.status().WithContext(context);
    group.layout = *layout;
    group.pictures.resize(gof.frame_count);
    return group;
  }

  /// The current key group's layout of `packing`, checked against HEAD's picture size.
  StatusOr<const DisplacementLayout*> LayoutOf(DisplacementPacking packing) {
    const StreamInfo& stream = reader_->header().streams[0];
    return geometry_->CheckedLayout(packing, key_group_ == 0, int(stream.width),
                                    int(stream.height));
  }

  /// A copy of `bytes` as a Uint8Array of the page's own.
  static val Copy(const std::vector<std::uint8_t>& bytes) {
    return val(emscripten::typed_memory_view(bytes.size(), bytes.data())).call<val>("slice");
  }

  std::unique_ptr<FetchedRanges> ranges_;  // a streamed file's bytes (null: in memory)
  std::optional<ContainerReader> reader_;
  std::optional<KeyGroupGeometry> geometry_;
  int key_group_ = -1;
  std::optional<KeyGroupGeometry> prepared_;  // the next key group, made ahead
  int prepared_key_group_ = -1;
  std::optional<WebGroup> group_;
  std::vector<std::uint8_t> bytes_;
  std::vector<Eigen::Vector3f> positions_;
  std::string error_;
};

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));

EMSCRIPTEN_BINDINGS(meshvid) {
  emscripten::class_<WasmDecoder>("WasmDecoder")
      .constructor<>()
      .function("open", &WasmDecoder::Open)
      .function("isOpen", &WasmDecoder::IsOpen)
      .function("beginStream", &WasmDecoder::BeginStream)
      .function("addBytes", &WasmDecoder::AddBytes)
      .function("firstGap", &WasmDecoder::FirstGap)
      .function("takeMissing", &WasmDecoder::TakeMissing)
      .function("openStream", &WasmDecoder::OpenStream)
      .function("groupSpan", &WasmDecoder::GroupSpan)
      .function("keyGroupSpan", &WasmDecoder::KeyGroupSpan)
      .function("preparedKeyGroup", &WasmDecoder::PreparedKeyGroup)
      .function("frameCount", &WasmDecoder::FrameCount)
      .function("declaredFrameCount", &WasmDecoder::DeclaredFrameCount)
      .function("frameRate", &WasmDecoder::FrameRate)
      .function("levels", &WasmDecoder::Levels)
      .function("gofCount", &WasmDecoder::GofCount)
      .function("keyGroupCount", &WasmDecoder::KeyGroupCount)
      .function("codecTag", &WasmDecoder::CodecTag)
      .function("metadataJson", &WasmDecoder::MetadataJson)
      .function("gofOfFrame", &WasmDecoder::GofOfFrame)
      .function("keyGroupOfGof", &WasmDecoder::KeyGroupOfGof)
      .function("gofFirstFrame", &WasmDecoder::GofFirstFrame)
      .function("gofFrameCount", &WasmDecoder::GofFrameCount)
      .function("baseBytes", &WasmDecoder::BaseBytes)
      .function("setKeyGroup", &WasmDecoder::SetKeyGroup)
      .function("prepareKeyGroup", &WasmDecoder::PrepareKeyGroup)
      .function("usePreparedKeyGroup", &WasmDecoder::UsePreparedKeyGroup)
      .function("currentKeyGroup", &WasmDecoder::CurrentKeyGroup)
      .function("loadGof", &WasmDecoder::LoadGof)
      .function("groupVideo", &WasmDecoder::GroupVideo)
      .function("pictureSamples", &WasmDecoder::PictureSamples)
      .function("pictureAddress", &WasmDecoder::PictureAddress)
      .function("decodePositions", &WasmDecoder::DecodePositions)
      .function("positions", &WasmDecoder::Positions)
      .function("triangles", &WasmDecoder::Triangles)
      .function("error", &WasmDecoder::Error);
}

}  // namespace
}  // namespace meshvid
