// A `meshvid render` run: one or more inputs (a .mvid, a capture's raw views, ground truth)
// rendered side by side from one camera, optionally coloured by their distance to ground
// truth, frame by frame into a PNG, a PNG per frame, or an MP4.
#ifndef MESHVID_TOOLS_RENDER_RENDER_JOB_H_
#define MESHVID_TOOLS_RENDER_RENDER_JOB_H_

#include <memory>
#include <string>
#include <vector>

#include "codec/common/progress.h"
#include "format/status.h"
#include "tools/io/mesh_sequence.h"
#include "tools/render/camera.h"
#include "tools/render/rgb_image.h"

namespace meshvid {

/// What to render and where.
struct RenderJobOptions {
  /// The panels, left to right: each a .mvid, a capture (manifest, pattern with {view}, .conf)
  /// or ground truth (NAME.obj + NAME.pc2, a folder, a pattern, scene:NAME).
  std::vector<std::string> inputs;
  /// OUT.png (the first frame of the range), a pattern with {frame} ending in .png (one PNG
  /// per frame) or OUT.mp4.
  std::string output;
  int level = -1;            ///< level of .mvid inputs (-1: finest)
  bool allow_partial = false;  ///< read a cut or damaged .mvid's readable frames
  int first_frame = 0;
  int end_frame = -1;        ///< one past the last (-1: as many as every input has)
  int width = 640;           ///< of each panel
  int height = 480;
  OrbitSpec orbit;
  std::string error_against;  ///< ground truth to colour the other panels' distance to
  float error_max_mm = 0;     ///< top of the colour scale (0: chosen from the first frame)
  bool labels = true;         ///< name each panel and the frame
  int crf = 20;               ///< MP4 quality (x264/x265 CRF)
};

/// What a run did.
struct RenderJobStats {
  int frames = 0;
  int width = 0;   ///< of the whole picture
  int height = 0;
  double seconds = 0;        ///< rendering and writing, inputs' decoding included
  float error_max_mm = 0;    ///< the colour scale's top, when colouring by error
  std::string video_codec;   ///< MP4 output: the encoder used
  /// Set when the frames asked for run past those every input has: what was drawn instead.
  std::string clipped_frames;
};

/// Opens one input of `meshvid render` (see RenderJobOptions::inputs).
StatusOr<std::unique_ptr<MeshSequence>> OpenRenderInput(const std::string& spec, int level,
                                                        bool allow_partial = false);

/// A short name for a panel: "input views", "ground truth" or the file name (and level).
std::string PanelLabel(const std::string& spec, int level);

/// Renders every frame of the range and writes the output.
StatusOr<RenderJobStats> RunRenderJob(const RenderJobOptions& options,
                                      const ProgressCallback& progress = {});

/// A round number >= `value` (1, 2 or 5 times a power of ten).
float RoundUpNicely(float value);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_RENDER_RENDER_JOB_H_
