// The per-frame baseline meshvid is measured against: what today's volumetric-video players
// stream. Every frame on its own: fuse its views (the same fusion the encoder uses for its
// base mesh), optionally decimate the fused mesh to a vertex count (players stream a mesh of
// a budgeted size, not the full fusion), code it with Draco (edgebreaker, position
// quantisation at several settings), decode it again. Each frame is fused once and reused for
// every setting.
#ifndef MESHVID_TOOLS_BENCH_BASELINE_H_
#define MESHVID_TOOLS_BENCH_BASELINE_H_

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "codec/common/camera.h"
#include "codec/common/mesh.h"
#include "codec/common/progress.h"
#include "codec/enc/fusion/surface_fusion.h"
#include "format/status.h"
#include "tools/io/capture.h"

namespace meshvid {

/// What the baseline runs.
struct BaselineOptions {
  /// Draco position quantisation settings, one coded sequence each.
  std::vector<int> position_bits = {8, 10, 12, 14};
  /// Vertex counts each fused frame is decimated to (quadric error, the encoder's decimation),
  /// each coded at every position_bits; empty: the full fused mesh.
  std::vector<std::size_t> vertex_targets;
  int draco_speed = 0;  ///< Draco encoding speed 0 (smallest) .. 10
  /// When the capture has colour: every coded mesh carries a colour per vertex
  /// (ColourVerticesFromViews) as a Draco attribute of 8 bits per channel, lossless, and its
  /// bytes are counted apart (BaselineSetting::colour_bytes_total).
  bool colour = true;
  SurfaceFusionOptions fusion;
  /// Decoded frames are written to `out_dir`/<BaselineSettingFolder>/f<frame:04>.ply (binary
  /// PLY) for the
  /// evaluator, and the Draco bitstreams beside them as f<frame:04>.drc (for
  /// DecodeDracoFrames); "" writes nothing.
  std::string out_dir;
};

/// One Draco setting over every frame.
struct BaselineSetting {
  int position_bits = 0;
  std::size_t target_vertices = 0;  ///< decimated to this many vertices; 0: full fused mesh
  std::size_t bytes_total = 0;      ///< sum of the Draco bitstreams (no container), colour included
  /// What colour adds to bytes_total: each frame coded with and without its colour attribute,
  /// the difference summed; 0 without colour.
  std::size_t colour_bytes_total = 0;
  double colour_seconds = 0;    ///< ColourVerticesFromViews of this setting's mesh, every frame
  double encode_seconds = 0;    ///< Draco encoding, every frame
  double decode_seconds = 0;    ///< Draco decoding (DecodeBaseMesh), every frame
  double vertices = 0;          ///< mean decoded vertices per frame
  double triangles = 0;         ///< mean decoded triangles per frame
  std::string pattern;          ///< decoded frames, e.g. "out/b10/f{frame:04}.ply"
};

/// What the baseline measured.
struct BaselineSummary {
  int frames = 0;
  double frame_rate = 0;
  double load_seconds = 0;  ///< reading the views of every frame
  double fuse_seconds = 0;  ///< FuseRangeMeshes, every frame
  double decimate_seconds = 0;  ///< decimation to every vertex target, every frame
  double colour_seconds = 0;    ///< ColourVerticesFromViews of every coded mesh, every frame
  std::vector<BaselineSetting> settings;
};

/// Gives `mesh` a colour per vertex from the views' vertex colours, measured as the encoder
/// measures its samples' colour, its lengths scaled to the mesh's size as the encoder's are
/// to the scene's: each vertex shoots along its normal into every view with colours
/// (MeasureDisplacements on the mesh as a lattice of level 0), the views are put on
/// one exposure (EstimateExposureGains) and fused (FuseColours); a vertex no view saw takes
/// its neighbours' colour, or the mean of the frame. `cameras` as MeasureDisplacements takes
/// them (may be empty).
Status ColourVerticesFromViews(std::span<const TriangleMesh> views,
                               std::span<const ViewCalibration> cameras, TriangleMesh* mesh);

/// The folder of a setting's frames under BaselineOptions::out_dir: "b<bits>" for the full
/// fused mesh, "v<target>-b<bits>" for a decimated one.
std::string BaselineSettingFolder(std::size_t target_vertices, int position_bits);

/// Runs the baseline on every frame of `capture`, reporting progress per frame ("baseline").
/// Fails with the frame number if a frame cannot be loaded, fused or coded.
StatusOr<BaselineSummary> RunBaseline(const CaptureSequence& capture,
                                      const BaselineOptions& options,
                                      const ProgressCallback& progress = {});

/// The summary as JSON text ({"frames", "frame_rate", "load_seconds", "fuse_seconds",
/// "decimate_seconds", "settings": [{"position_bits", "target_vertices", "bytes_total", ...}]}).
std::string BaselineSummaryToJson(const BaselineSummary& summary);

/// Parses BaselineSummaryToJson's output; `name` is used in messages.
StatusOr<BaselineSummary> ParseBaselineSummary(const std::string& text, const std::string& name);

/// What decoding a folder of Draco bitstreams cost.
struct DracoDecodeSummary {
  int frames = 0;
  std::size_t bytes_total = 0;
  double seconds = 0;   ///< DecodeBaseMesh only, every frame (file reading excluded)
  double vertices = 0;  ///< mean per frame
};

/// Decodes every f<frame>.drc of `folder` in name order (colours too, where a stream has
/// them), as a per-frame player would, timing
/// the decoding alone. Fails naming the file that does not decode, or if there is none.
StatusOr<DracoDecodeSummary> DecodeDracoFrames(const std::string& folder);

/// Reads a whole file; fails naming the file.
StatusOr<std::string> ReadTextFile(const std::string& path);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_BASELINE_H_
