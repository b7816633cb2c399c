#pragma once
// The CPU peers `glint bench post` measures glint's GPU effects against, in the same run:
// OpenCV's equivalents and FFTW. Private to bench/; OpenCV's heavy headers stay in
// post_peers.cpp. Each function prepares its buffers from the input and returns the work
// of one frame, to be timed (the closure owns everything it needs).
#include "glint/core/math.h"
#include "glint/image/image.h"

#include <functional>
#include <string>

namespace glint::bench::peers {

using Work = std::function<void()>;

/// The common colour-matrix sepia (cv::transform, 8-bit) — the matrix way, not YIQ.
Work opencvSepia(const Image& rgba);
/// cvtColor to float gray, cv::Sobel x and y (BORDER_REPLICATE), cv::magnitude, to 8 bits.
Work opencvSobel(const Image& rgba);
/// Kuwahara from OpenCV's parts (OpenCV has none): cv::boxFilter of I and I² (the
/// statistics pass), then the four-quadrant selection in a cv::parallel_for_.
Work opencvKuwahara(const Image& rgba, int quadrant = 3);
/// Luma, cv::dft (complex output), magnitude, log: the spectrum view.
Work opencvSpectrum(const Image& rgba);
/// R, G and B through cv::dft, cv::mulSpectrums with H, cv::idft: a frequency-domain filter.
Work opencvFrequencyFilter(const Image& rgba);
/// A 2D complex single-precision FFT of `size` with FFTW (FFTW_MEASURE plan made here,
/// every core through fftw3f_threads).
Work fftwForward(ivec2 size);
/// The same transform with cv::dft (complex input).
Work opencvDft(ivec2 size);
/// Threads the peers use (OpenCV's and FFTW's), for the notes.
int peerThreads();

}  // namespace glint::bench::peers
