// From per-patch radiosity to pictures (rad-shade): views, smoothing, rasterising, output.
#pragma once
#include "radiosity/image_io.hpp"
#include "radiosity/raster.hpp"
#include "radiosity/smoothing.hpp"
#include "radiosity/view.hpp"
