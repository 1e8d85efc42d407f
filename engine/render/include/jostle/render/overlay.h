// jostle/render/overlay.h: the debug overlay. Draws what the world sees, read through a const
// World: every collider's outline (coloured by body kind), the broadphase's fat bounds,
// contact points with their normals and MTD arrows, bullet paths and swept circles.
#pragma once

#include "jostle/render/renderer.h"
#include "jostle/world.h"

namespace jostle {

struct OverlayOptions {
    bool colliders = true;
    bool broadphase = false;  // fat bounds of every proxy
    bool contacts = true;     // point, normal (10 px), and the MTD push as an arrow
    bool paths = true;        // bullets' segments and fast circles' sweeps of the last step
    float thickness = 1.0f;   // line width in image pixels
};

// Colours, so tests and legends agree with what is drawn.
inline constexpr Color kOverlayStatic{160, 160, 160, 255};
inline constexpr Color kOverlayKinematic{80, 160, 255, 255};
inline constexpr Color kOverlayDynamic{80, 255, 80, 255};
inline constexpr Color kOverlayBullet{255, 255, 80, 255};
inline constexpr Color kOverlayTrigger{255, 80, 255, 255};
inline constexpr Color kOverlayBroadphase{90, 90, 90, 255};
inline constexpr Color kOverlayContact{255, 60, 60, 255};
inline constexpr Color kOverlayMtd{255, 160, 0, 255};
inline constexpr Color kOverlayPath{255, 255, 255, 255};

Color overlay_color(BodyKind kind);

// Draws the overlay into the frame being drawn (between begin_frame and end_frame).
void draw_overlay(Renderer& renderer, const World& world, const OverlayOptions& options = {});

}  // namespace jostle
