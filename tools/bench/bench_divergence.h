// The divergence check of a bench record: meshvid at the encoder's default settings against
// the baseline's best setting, frame by frame (DivergenceCheck in bench_record.h). Goals: on
// at least kDivergenceShareGoal of the frames meshvid's accuracy RMS is at most
// kDivergenceRatioLimit times the baseline's, and its D1 PSNR (mean of frames) is at least
// the baseline's best.
#ifndef MESHVID_TOOLS_BENCH_BENCH_DIVERGENCE_H_
#define MESHVID_TOOLS_BENCH_BENCH_DIVERGENCE_H_

#include <string>

#include "tools/bench/bench_record.h"

namespace meshvid {

/// The codec and quality `meshvid encode` uses when given neither (EncoderOptions' defaults:
/// "hevc", 40).
std::string DefaultCodecName();
/// See DefaultCodecName.
int DefaultQuality();

/// The level of the default point: the finest level the default encode's file stores (its
/// BenchEncode's `levels`, what `meshvid decode` and `meshvid eval` decode by default), or,
/// without that encode in the record, the finest level among the default codec and quality's
/// points; -1 if there is neither.
int DefaultPointLevel(const BenchRecord& record);

/// The meshvid point of the default codec and quality at DefaultPointLevel, ok or not; nullptr
/// if the record has none.
const BenchPoint* FindDefaultPoint(const BenchRecord& record);

/// The baseline's best setting: among the successful baseline points, the one with the highest
/// D1 PSNR of RecordPsnrKind's kind (the mean of frames, unless the record is older); of equal
/// PSNRs the one with fewer bytes per frame. nullptr if no baseline point succeeded.
const BenchPoint* FindBaselineBest(const BenchRecord& record);

/// Sets record.divergence from the record's points: the default point against the baseline's
/// best, per frame ratio = meshvid accuracy RMS / baseline accuracy RMS on the same frame (0 / 0
/// counts as 1; a frame where either figure is missing counts as outside the limit and as the
/// worst), over the frames both points have; and their D1 PSNRs. What is missing is said in
/// the note.
void ComputeDivergence(BenchRecord& record);

/// One line for a run's log: "divergence of hevc q40 L2 against the baseline's 14 bits:
/// 28/30 frames within 1.25x (93.3%, goal 95%: missed), worst frame 17 (2.31x: ...), D1 PSNR
/// 62.10 against 65.30 dB (missed)", or what is missing.
std::string DescribeDivergence(const DivergenceCheck& check);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_BENCH_DIVERGENCE_H_
