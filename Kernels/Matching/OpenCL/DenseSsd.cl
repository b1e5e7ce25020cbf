// Coarse weighted SSD of a query window at sixteen neighbouring offsets per
// work-item (explicit float16, so the CPU device vectorises it), summed over the
// given terms only: the same sums in the same order as DenseMatcher::coarseSsd().
// One launch covers every oriented exemplar: work-item row r is row rowY[r] of
// oriented exemplar rowOriented[r]; images, run masks and outputs of all
// exemplars are concatenated, located by the per-exemplar start tables.
#pragma OPENCL FP_CONTRACT OFF

__kernel void coarseSsd(__global const float* images, __global const int* rowOriented,
  __global const int* rowY, __global const int* imageStart, __global const int* strides,
  __global const int* offsetsXs, __global const int* runStart, __global const int* outStart,
  __global const int* rows, __global const int* columns, __global const float* heights,
  __global const float* weights, const int terms, __global const uchar* runs,
  __global float* out)
{
  const int g = (int)get_global_id(0);
  const int o = rowOriented[get_global_id(1)];
  const int y = rowY[get_global_id(1)];
  const int offsetsX = offsetsXs[o];
  const int groups = (offsetsX + 15) / 16;
  const int x0 = g * 16;
  if (g >= groups || runs[runStart[o] + y * groups + g] == 0)
  {
    return;
  }
  __global const float* image = images + imageStart[o];
  const int stride = strides[o];
  float16 acc = (float16)(0.0f);
  for (int e = 0; e < terms; ++e)
  {
    const float16 cells = vload16(0, image + (y + rows[e]) * stride + x0 + columns[e]);
    const float16 d = (float16)(heights[e]) - cells;
    acc += ((float16)(weights[e]) * d) * d;
  }
  float lanes[16];
  vstore16(acc, 0, lanes);
  __global float* costs = out + outStart[o] + y * offsetsX;
  for (int l = 0; l < 16 && x0 + l < offsetsX; ++l)
  {
    costs[x0 + l] = lanes[l];
  }
}
