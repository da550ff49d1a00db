// `meshvid eval`: measures a test sequence (a mesh sequence or a capture's raw scans) against
// ground truth, frame by frame: D1/D2 PSNR, RMS accuracy and completeness, Hausdorff distance
// and coverage.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "tools/cli/commands.h"
#include "tools/cli/json_text.h"
#include "tools/cli/mvid_input.h"
#include "tools/cli/option_checks.h"
#include "tools/cli/terminal.h"
#include "tools/eval/eval_source.h"
#include "tools/eval/evaluation.h"
#include "tools/io/file_pattern.h"
#include "tools/sim/ground_truth.h"

namespace meshvid::cli {
namespace {

/// The command line of `meshvid eval`.
struct EvalArguments {
  std::string ref;
  std::string test;
  std::string frames;
  std::string json;
  std::size_t samples = 200000;
  double coverage_tolerance = -1;
  double peak = -1;
  std::uint64_t seed = 1;
  std::optional<int> ref_first;  ///< unset: the reference and the test start together
  int level = -1;
  bool quiet = false;
  bool allow_partial = false;
};

int RunEval(const EvalArguments& args) {
  StatusOr<std::unique_ptr<MeshSequence>> ref = OpenGroundTruth(args.ref);
  if (!ref.ok()) return ReportError(ref.status().WithContext("--ref " + args.ref));
  StatusOr<std::unique_ptr<MeshSequence>> test =
      OpenEvalTestSource(args.test, args.level, args.allow_partial);
  if (!test.ok()) return ReportError(test.status().WithContext("--test " + args.test));
  if (args.allow_partial) WarnIfPartial(args.test);

  EvalOptions options;
  options.samples = args.samples;
  options.seed = args.seed;
  options.coverage_tolerance = args.coverage_tolerance;
  options.peak = args.peak;
  options.ref_first = args.ref_first;
  if (!args.frames.empty()) {
    StatusOr<std::pair<int, int>> range = FramesOption(args.frames, (*test)->frame_count());
    if (!range.ok()) return ReportError(range.status());
    options.first_frame = range->first;
    options.end_frame = range->second;
  }

  ProgressBar bar(args.quiet);
  StatusOr<EvalResult> result = EvaluateSequences(**ref, **test, options, bar.Callback());
  bar.Finish();
  if (!result.ok()) return ReportError(result.status());
  if (!args.json.empty()) {
    // The descriptions name files, which may not be UTF-8 as the JSON writer needs.
    result->ref_description = ToValidUtf8(result->ref_description);
    result->test_description = ToValidUtf8(result->test_description);
    const Status written = WriteJsonOutput(args.json, EvalResultToJson(*result));
    if (!written.ok()) return ReportError(written);
  }
  // The table goes to stdout, unless the JSON does.
  std::fputs(FormatEvalTable(*result).c_str(), args.json == "-" ? stderr : stdout);
  return 0;
}

}  // namespace

void AddEvalCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<EvalArguments>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Measure a test sequence against ground truth, per frame and on average: D1/D2 PSNR\n"
      "(MPEG pc_error, peak p = ground truth bounding-box diagonal over all its frames),\n"
      "RMS accuracy (test->ref), RMS completeness (ref->test), Hausdorff, coverage.\n"
      "An exact frame has PSNR inf. A sequence's PSNR is given twice: of the mean MSE\n"
      "(\"mean MSE\"; JSON mean.d1_psnr) and as the mean of per-frame PSNRs, MPEG CTC's\n"
      "average, each frame counted as at most 100 dB (\"mean of frames\"; JSON\n"
      "mean.d1_psnr_mean_of_frames).\n"
      "Colour, where both sides have it: PSNR of 8-bit BT.709 Y and of Y Cb Cr weighted\n"
      "6:1:1 (MPEG), against the reference's colour at the nearest surface point. A\n"
      "sequence's colour PSNRs are only ever the mean of per-frame PSNRs (each at most\n"
      "100 dB): JSON mean.y_psnr, mean.yuv_psnr, beside D1's mean MSE figures.");
  cmd->add_option("--ref", args->ref,
                  "Ground truth: scene:NAME, NAME.obj (+NAME.pc2), a folder or a {frame} pattern")
      ->required();
  cmd->add_option("--test", args->test,
                  "Test: a .mvid (decoded at --level), a mesh sequence (as --ref) or a capture\n"
                  "(manifest.json, .conf, a {frame}+{view} pattern: the union of its views)")
      ->required();
  cmd->add_option("--level", args->level,
                  "Level at which a .mvid test is decoded (default: the finest stored)")
      ->check(AtLeastZero());
  cmd->add_option("--frames", args->frames,
                  "The test's frame range A:B (half-open), A:, :B or N")
      ->type_name("A:B");
  cmd->add_option("--ref-first", args->ref_first,
                  "The reference frame the test's frame 0 is measured against: N for a file\n"
                  "encoded with --frames N:... from a capture of the whole reference (test\n"
                  "frame t against reference frame N + t; the PSNR peak stays the whole\n"
                  "reference's). Given, even as 0, the reference may run on past the test's\n"
                  "last frame; not given, both must have as many frames")
      ->check(AtLeastZero());
  cmd->add_option("--json", args->json, JsonOptionHelp("Also write the results"))
      ->type_name("FILE|-");
  cmd->add_option("--samples", args->samples, "Samples per surface and frame")
      ->default_val(200000)
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
  cmd->add_option("--coverage-tol", args->coverage_tolerance,
                  "Coverage tolerance in the data's units (default 0.25% of p)")
      ->check(AtLeastZero());
  cmd->add_option("--peak", args->peak, "Override the PSNR peak p (data units)")
      ->check(AboveZero());
  cmd->add_option("--seed", args->seed, "Sampling seed")->default_val(1);
  AddAllowPartialFlag(cmd, &args->allow_partial);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar (the report is still printed)");
  cmd->callback([args, exit_code] { *exit_code = RunEval(*args); });
}

}  // namespace meshvid::cli
