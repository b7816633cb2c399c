#pragma once
// glint/raster/raster.h — the reference CPU implementation of the OpenGL pipeline.
//
// Contents
//   state.h         State: GL's rasterization/per-fragment state with GL's initial values
//   framebuffer.h   Framebuffer: RGBA float colour, float depth, 8-bit stencil, overdraw count;
//                   colorImage / depthImage / stencilImage / overdrawImage
//   geometry.h      the lecture math: viewport transform, clipping, edge equations,
//                   plane equations, barycentrics, 1/256 fixed point and the tie rule
//   fragment_ops.h  stencil test and ops, depth test, blending, processFragment
//   pipeline.h      drawTriangles: assembly → clip → window → raster → shade → fragment ops
//   visualize.h     pictures of the edge equations (diverging colour map, zero line)
//
// No OpenGL inside: it is the oracle that GL tests compare against (stencil counts
// for shadow volumes, depth for depth-test scenes) and a teaching tool, so every
// step favours clarity over speed and follows the GL 4.5 core specification.

#include "glint/raster/fragment_ops.h"
#include "glint/raster/framebuffer.h"
#include "glint/raster/geometry.h"
#include "glint/raster/pipeline.h"
#include "glint/raster/state.h"
#include "glint/raster/visualize.h"
