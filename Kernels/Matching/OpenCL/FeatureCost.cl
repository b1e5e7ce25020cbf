// Feature cost of every candidate variant against one target site: the same
// arithmetic, in the same order, as candidateCost() in FeatureCost.cxx.
#pragma OPENCL FP_CONTRACT OFF

#define MAX_ARMS 4
#define ALONG 16
#define ACROSS 17
#define NOISE 3
#define PI_F 3.14159265358979f
#define LANDFORM_SAMPLES 25.0f

// Query layout in `q`: angles[4], along[4*16], across[4*17], noise[3].
#define Q_ANGLES 0
#define Q_ALONG (Q_ANGLES + MAX_ARMS)
#define Q_ACROSS (Q_ALONG + MAX_ARMS * ALONG)
#define Q_NOISE (Q_ACROSS + MAX_ARMS * ACROSS)

float laneSum(float16 v)
{
  // Lanes added in order 0..15, as the CPU reference does.
  float s = 0.0f;
  s += v.s0; s += v.s1; s += v.s2; s += v.s3; s += v.s4; s += v.s5; s += v.s6; s += v.s7;
  s += v.s8; s += v.s9; s += v.sa; s += v.sb; s += v.sc; s += v.sd; s += v.se; s += v.sf;
  return s;
}

__kernel void featureCost(__global const int* kind, __global const int* type,
  __global const int* arms, __global const float* angles, __global const float* along,
  __global const float* across, __global const float* noise, __global const float16* descriptor,
  __global const float16* landform, __constant const float* q, __constant const float16* qd,
  __constant const float16* qw, __constant const float16* ql, __constant const float16* qlw,
  const int qType, const int qKind, const int qArms, const float4 weights,
  const float landformWeight, const int verticalOffset, const float invScale2, const uint n,
  __global float* out)
{
  const uint c = get_global_id(0);
  if (c >= n)
  {
    return;
  }
  // A candidate of another type, kind or number of arms is never chosen
  // (PatchMatcher::matchFeature skips it): the penalty alone, nothing computed.
  if (type[c] != qType || kind[c] != qKind || arms[c] != qArms)
  {
    out[c] = 1.0e6f;
    return;
  }
  // Overlap: 16 lanes accumulate blocks k, k + 16, ...
  float16 sw16 = (float16)(0.0f);
  float16 swd16 = (float16)(0.0f);
  float16 swd216 = (float16)(0.0f);
  for (int k = 0; k < 16; ++k)
  {
    const float16 diff = qd[k] - descriptor[c * 16 + k];
    const float16 wk = qw[k];
    sw16 += wk;
    swd16 += wk * diff;
    swd216 += (wk * diff) * diff;
  }
  const float sw = laneSum(sw16);
  const float swd = laneSum(swd16);
  const float swd2 = laneSum(swd216);
  float overlap = 0.0f;
  if (sw > 0.0f)
  {
    overlap = verticalOffset ? (swd2 - swd * swd / sw) / sw : swd2 / sw;
    overlap *= invScale2;
  }
  const float costOverlap = weights.w * overlap;
  float best = 3.4e38f;
  const int alignments = qArms > 1 ? qArms : 1;
  for (int s = 0; s < alignments; ++s)
  {
    float profile = 0.0f;
    float samples = 0.0f;
    float angle = 0.0f;
    for (int a = 0; a < qArms; ++a)
    {
      const int b = (a + s) % qArms;
      float da = q[Q_ANGLES + a] - angles[c * MAX_ARMS + b];
      da = remainder(da, 2.0f * PI_F) / PI_F;
      angle += da * da;
      for (int k = 0; k < ALONG; ++k)
      {
        const float t = q[Q_ALONG + a * ALONG + k];
        if (!isnan(t))
        {
          const float d = t - along[(c * MAX_ARMS + b) * ALONG + k];
          profile += d * d;
          samples += 1.0f;
        }
      }
      for (int k = 0; k < ACROSS; ++k)
      {
        const float t = q[Q_ACROSS + a * ACROSS + k];
        if (!isnan(t))
        {
          const float d = t - across[(c * MAX_ARMS + b) * ACROSS + k];
          profile += d * d;
          samples += 1.0f;
        }
      }
    }
    const float cf = samples > 0.0f ? profile / samples * invScale2 : 0.0f;
    const float ca = qArms > 0 ? angle / (float)qArms : 0.0f;
    best = fmin(best, weights.x * cf + weights.y * ca);
  }
  float cn = 0.0f;
  for (int l = 0; l < NOISE; ++l)
  {
    const float a = q[Q_NOISE + l];
    const float f = noise[c * NOISE + l];
    if (a > 0.0f)
    {
      const float d = (a - f) / (a + f);
      cn += d * d;
    }
  }
  // Landform: 16 lanes over samples k, k + 16.
  float16 swl216 = (float16)(0.0f);
  for (int k = 0; k < 2; ++k)
  {
    const float16 diff = ql[k] - landform[c * 2 + k];
    swl216 += (qlw[k] * diff) * diff;
  }
  const float cl = laneSum(swl216) / LANDFORM_SAMPLES * invScale2;
  out[c] = best + weights.z * cn + costOverlap + landformWeight * cl;
}
