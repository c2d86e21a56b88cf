#!/usr/bin/env bash
# Runs the test suite under AddressSanitizer + UndefinedBehaviorSanitizer, and the tests that run
# threads under ThreadSanitizer. Any sanitizer report fails the run.
# Usage: scripts/sanitize.sh [asan|tsan]...   (default: both)
#
# Each suite keeps to what its sanitizer can find (issue 26: CI must fit 50 minutes on the slowest
# processor). The long physics runs (the torture scenarios, the level-5 and level-6 settles) run once,
# in release (scripts/test.sh): the code they drive runs under ASan in the short tests too, and on the
# slowest processor they were most of ASan's 22 minutes. ThreadSanitizer can only find races where
# threads run: in the renderer (TBB tiles: every render test) and in the membrane's threaded substep
# (the core tests whose names say Thread, Parallel, DampedSymplecticEuler or FusedSubstep; name a test
# of new threaded core code so). Single-threaded physics under TSan checks nothing and took 20 minutes
# (BulkSlime alone 15).
set -euo pipefail
cd "$(dirname "$0")/.."
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:suppressions=$PWD/scripts/asan.supp"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp"
# Suites named *Long (ContactLong) are long runs too.
long_physics='Torture|DefaultsHoldLevel6|DefaultsHold.BallFallsSettlesSoftAndRound/5|[A-Za-z]+Long\.'
# Seconds of simulated physics each, 12-40 s apiece under ASan (F25): the press, the pinch, the drop
# with two other integrators, Lamb's modes, energy, the stiffer dampers, the sticky floor. The code they
# drive runs under ASan in the short tests (Hands, Projective, BulkSlime's others, the scenarios). The
# press recovery (7 s at resolution 3: 70 s under ASan on the F26) drives the press stop, which PressStop
# runs under ASan in a second.
# SlowTwoHandPull (7 s of a pull each, 22-26 s under ASan) is left to release for a second reason: at -O1
# the pulled strand takes another path and tears near a hand at 2.7 s (14 cm), with damage and without,
# where release draws it out (no tear even at a tear stretch of 2.4 against 2.5). An open fragility of the
# tear criterion near the grips, not a memory error: ASan and UBSan report nothing in those runs.
# Two more are left to release for the same reason, rounding that -O1 changes (not memory: nothing
# reported): the fold (SelfContact.AFoldDoesNotPassThroughItself: 40 of 77 points inside two sheets at -O1,
# 9 in release, the bound 15) and the clear slime's caustic peak (Caustics.ClearSlimesCausticKeepsThePeak...:
# at -O1 the map's brightest cell lies 16 mm from the reference's, on the cusp's other arm, in release
# the same cell). docs/physics.md and docs/rendering.md say so. ThreadSanitizer's build is -O1 too.
# And the README clip's run (ReadmeClip.*): at -O1 its pull tears three times and a bead stays apart at the
# release (2 pieces), where release tears once and merges (1).
rounding_sensitive='SlowTwoHandPull\.|SelfContact\.AFoldDoesNotPassThroughItself|Caustics\.ClearSlimesCausticKeepsThePeakAndTheCusp|ReadmeClip\.'
long_under_asan="$rounding_sensitive|"'BulkSlime\.(APressLeaves|HeldUpByAPinch|Lamb|EnergyIsKept|FallsJiggles)|DefaultBall\.ComesToRest|StifferDamper\.|FloorAdhesion\.TheStickyDefaultStretches|ProjectiveStiffRest\.|Projective\.StiffRestHeight|PressRecovery\.'
# The render tests whose time is a single-threaded brute-force oracle (every pixel or ray against every
# triangle) over classes that start no thread (the pencil grid, the exit walk, the screen footprint) or
# whose threaded part (SlimeGeometry::update) every renderer test runs too: under ThreadSanitizer they
# were 210 of the render suite's CPU seconds (F25) and can find no race. ASan and release still run them.
single_threaded_oracles='PencilGrid\.|ExitWalk\.|ScreenFootprint\.|PrimaryVisibility\.EqualsTheEyesGrid|SlimeGeometry\.EveryDepth'
# Image tests whose reference is a slime settled by seconds of physics: at -O1 its shape takes other
# rounding than release's -O3 and the picture moves at the silhouette (ClearSlimeLowerHalf: 7.7 % of the
# pixels under ASan). Release holds them to their references; under the sanitizers the same tracing runs
# in ClearSlimeAtTheCapTakesTheSkyNotBlack, which compares renders of one build with each other.
settled_references='Golden\.ClearSlimeLowerHalfShowsTotalInternalReflection'
for preset in "${@:-asan tsan}"; do
  for p in $preset; do
    cmake --preset "$p" -G Ninja >/dev/null
    case "$p" in
      asan)
        cmake --build --preset asan --target slime core_tests render_tests app_tests
        # Processes that load Mesa's GL driver (the window, the EGL snapshot) run without LeakSanitizer:
        # the driver's own allocations are reported only after it is unloaded at exit, from an
        # "<unknown module>" no suppression can name. ASan's memory errors and UBSan stay on for them.
        gl='HeadlessViewer|ViewerCheck|UiSnapshot|FrameCompositor|^viewer_'
        ctest --preset asan -j2 --timeout 900 -E "$gl|$long_physics|$long_under_asan|$settled_references"
        ASAN_OPTIONS="${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" ctest --preset asan -j2 --timeout 900 -R "$gl" ;;
      tsan)
        cmake --build --preset tsan --target core_tests render_tests
        # FusedSubstep at level 6 runs many thousands of TBB passes, each reported and suppressed inside
        # Debian's uninstrumented libtbb (minutes per simulated second); level 3 keeps its passes here.
        ctest --preset tsan -j2 --timeout 900 -L '^render$' -E "$long_physics|$single_threaded_oracles|$settled_references|$rounding_sensitive"
        ctest --preset tsan -j2 --timeout 900 -L '^core$' -R 'Thread|Parallel|DampedSymplecticEuler|FusedSubstep' \
          -E 'FusedSubstep.MatchesThePassByPassOne/6' ;;
    esac
  done
done
