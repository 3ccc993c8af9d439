#pragma once
// Random frame scenes for cross-checks, as TOML text, of the four kinds of the bundled
// frame scenes, each drawn in its own axes and then turned by a random angle (so that
// contacts, supports and loads point in every direction):
//   PostOnBeam   a post (sometimes two struts joined rigidly) clamped at its top, its tip
//                above a node of a beam on clamped or pinned supports;
//   ApexOnStop   two or three legs on clamped or pinned feet meeting at a rigid or pinned
//                apex joint, pushed toward a clamped stop from a random direction;
//   PortalOnStop a portal frame (clamped or pinned feet, rigid or pinned corners, never a
//                mechanism) swaying toward a stop at its corner;
//   FloatingBeam a beam held only by three contacts: two posts below and a stop at one
//                end, loaded into all three.
// Gaps are zero (the normal is then given) or positive; contacts are written either way
// round (a and b swapped, the normal reversed), at "NAME.from/.to" or "NAME@k". Loads are
// sized so that some contacts close and some stay open, and every scene has a unique
// solution.

#include <random>
#include <string>

namespace fetic::testing {

enum class FrameKind { PostOnBeam, ApexOnStop, PortalOnStop, FloatingBeam };

std::string random_frame_scene(std::mt19937& rng, FrameKind kind);

}  // namespace fetic::testing
