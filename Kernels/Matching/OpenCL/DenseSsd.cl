// Coarse weighted SSD of a query window at sixteen neighbouring offsets per
// work-item (explicit float16, so the CPU device vectorises it), summed over the
// query's known blocks only: the same sums in the same order as
// DenseMatcher::coarseCosts().
#pragma OPENCL FP_CONTRACT OFF

__kernel void coarseSsd(__global const float* image, const int stride, const int offsetsX,
  const int offsetsY, __global const int* rows, __global const int* columns,
  __global const float* heights, __global const float* weights, const int terms,
  __global const uchar* groupValid, __global float* out)
{
  const int g = (int)get_global_id(0);
  const int y = (int)get_global_id(1);
  const int groups = (offsetsX + 15) / 16;
  const int x0 = g * 16;
  if (y >= offsetsY || x0 >= offsetsX || groupValid[y * groups + g] == 0)
  {
    return;
  }
  float16 acc = (float16)(0.0f);
  for (int e = 0; e < terms; ++e)
  {
    const float16 cells = vload16(0, image + (y + rows[e]) * stride + x0 + columns[e]);
    const float16 d = (float16)(heights[e]) - cells;
    acc += ((float16)(weights[e]) * d) * d;
  }
  float lanes[16];
  vstore16(acc, 0, lanes);
  for (int l = 0; l < 16 && x0 + l < offsetsX; ++l)
  {
    out[y * offsetsX + x0 + l] = lanes[l];
  }
}
