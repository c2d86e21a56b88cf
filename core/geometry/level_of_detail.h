// slime.level=auto: the smallest icosphere level whose geometric error is invisible at the slime's
// size on screen ("model no more than the scene needs", SPEC §8).
//
// The geometric error of a level is its sagitta: how far the flat faces sink below the sphere they
// approximate, δ_L·R with δ_L = 1 − min over faces of (distance from the centre to the face's plane)/R
// (measured on makeIcosphere; δ_L ≈ 0.07·4^−L for L ≥ 2: it quarters with each level). Seen from a
// distance d with a vertical field of view φ on an image H pixels high, one metre spans
// H / (2 d tan(φ/2)) pixels, so the error on screen is
//   e_L = δ_L · R · H / (2 d tan(φ/2))  pixels.
// The threshold kInvisibleSagittaPixels is the one `slime bench accuracy` justifies (docs/bench,
// README): the largest on-screen sagitta at which the mesh's image was still indistinguishable from
// the analytic sphere's.
#pragma once

#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// Sagitta in pixels below which the mesh looks like the sphere. Measured by `slime bench accuracy`
// at the default view (smooth normals, the sphere at the same depth as reference, the visibility rule
// of app/bench/render/bench_accuracy.h): level 4 (sagitta 0.136 px) is invisible, level 3 (0.54 px) is not. A
// quarter pixel sits between the two with margin on both sides.
constexpr double kInvisibleSagittaPixels = 0.25;

// δ_L: the sagitta of level L relative to the radius (levels beyond the table quarter per level).
double icosphereSagitta(int level);

// Pixels one metre spans, at `distance` from the eye, on an image `imageHeight` pixels high.
double pixelsPerMetre(double distance, double fovDegrees, int imageHeight);

// Vertex motion in pixels below which the viewer does not trace the slime again: a twenty-fifth of
// kInvisibleSagittaPixels. Every vertex moved this far in random directions changes 0.06 % of the
// pixels by more than 2 steps of 8-bit sRGB (a one-pixel move: 7.5 %), invisible by the same rule
// (tests/render/trace/invariant_test.cpp). The viewer compares against the vertices it last drew, so slow
// creep is drawn once it adds up.
constexpr double kInvisibleMotionPixels = 0.01;

// Creep in pixels, measured from the vertices a still image's refinement started from, below which the
// viewer keeps refining that image instead of tracing it again. Judged by the refined image (16
// samples a pixel, the caustic map finished), not the one-sample frame's pixel centres: the creeps of a
// resting slime (a slide, a spreading) moved this far change under 0.5 % of its pixels by more than 2
// steps of 8-bit sRGB, the floor seen through the lens and the caustic included: half what the level of
// detail's rule calls invisible (tests/render/trace/invariant_test.cpp, figures in docs/rendering.md).
constexpr double kStillMotionPixels = 0.1;

// How far, in pixels, the vertex that moved most between `drawn` and `now` appears to move: its
// displacement seen at the nearest depth of `now`'s bounding sphere from the eye. Infinite when
// the two differ in size or the eye is inside that sphere (nothing then bounds the motion on screen).
double largestMotionPixels(const std::vector<glm::dvec3>& drawn, const std::vector<glm::dvec3>& now,
                           const glm::dvec3& eye, double fovDegrees, int imageHeight);

// e_L in pixels for a slime of `radius` whose centre is `distance` from the eye (same units).
double projectedSagittaPixels(int level, double radius, double distance, double fovDegrees, int imageHeight);

// The smallest level in [0, kMaxLevel] with e_L ≤ maxErrorPixels; kMaxLevel when none is small enough.
// A degenerate view (distance ≤ radius, no pixels) also gets kMaxLevel.
int chooseLevel(double radius, double distance, double fovDegrees, int imageHeight,
                double maxErrorPixels = kInvisibleSagittaPixels);

// The level the slime is built at: slime.level, or with slime.level=auto (autoLevel) chooseLevel for
// the resting ball (its centre one radius above the floor below slime.position) seen by the camera.
int effectiveLevel(const Settings& settings);

}  // namespace slime
