// The one place the bulk body's element precision is chosen (issue 27, item 6): the per-block rest data
// and Maxwell state (bulk_body.h's TetBlock, MaxwellBlock, MaxwellMapBlock) are stored in ElementReal, and
// the step's element arithmetic (tet_lanes.h, element_pass.h) runs in ElementReal lanes. Positions,
// velocities, the gathered edges' differences and the force sums stay double; so does the frequency
// estimate's finite difference (element_pass.h's elementForcesInDouble).
#pragma once

namespace slime {

#if defined(SLIME_ELEMENT_REAL_DOUBLE)  // (-DSLIME_ELEMENT_REAL_DOUBLE: the same code in double, to measure against)
using ElementReal = double;
#else
using ElementReal = float;
#endif

}  // namespace slime
