// The one place the bulk body's element precision is chosen (issue 27, item 6): the per-block rest data
// and Maxwell state (bulk_body.h's TetBlock, MaxwellBlock, MaxwellMapBlock) are stored in ElementReal, and
// the step's element arithmetic (tet_lanes.h, element_pass.h) runs in ElementReal lanes. Positions,
// velocities, the gathered edges' differences and the force sums stay double; so does the frequency
// estimate's finite difference (element_pass.h's elementForcesInDouble).
//
// Chosen by measurement on both kinds of processor (docs/performance.md, "Issue 27, item 6"): with
// AVX-512, 16 float lanes made the settings 1.02–1.21× cheaper than 8 double lanes (resolution 4
// the most: half the bytes streamed); on AVX2, 8 float lanes were 0.85–1.02× of 4 double lanes (the
// conversions at the gather and scatter cost more than the halved arithmetic saves), so double there.
#pragma once

namespace slime {

#if defined(__AVX512F__) && !defined(SLIME_ELEMENT_REAL_DOUBLE)  // (-DSLIME_ELEMENT_REAL_DOUBLE: to measure against)
using ElementReal = float;
#else
using ElementReal = double;
#endif

}  // namespace slime
