#define CL_TARGET_OPENCL_VERSION 120
#include "OpenClMatcher.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "Matching/OpenClSources.h"

#include <CL/cl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace tsynth
{
namespace
{

void check(cl_int status, const char* what)
{
  if (status != CL_SUCCESS)
  {
    throw Error(
      std::string("OpenCL failed to ") + what + " (error " + std::to_string(status) + ").");
  }
}

// The smallest buffer made: OpenCL refuses empty ones, and a few bytes cost nothing.
constexpr std::size_t kMinBufferBytes = 16;

// A cl_mem released when it goes.
class DeviceBuffer
{
public:
  DeviceBuffer() = default;
  // With host data, the buffer starts as a copy of its `bytes` bytes.
  DeviceBuffer(cl_context context, cl_mem_flags flags, std::size_t bytes, const void* host)
  {
    // CL_MEM_COPY_HOST_PTR copies the whole (padded) buffer from the host pointer:
    // fewer bytes than that go through a zeroed block of the padded size, so the
    // driver never reads past the caller's data.
    std::array<unsigned char, kMinBufferBytes> padded{};
    if (host != nullptr && bytes > 0 && bytes < kMinBufferBytes)
    {
      std::memcpy(padded.data(), host, bytes);
      host = padded.data();
    }
    cl_int status = CL_SUCCESS;
    mem_ = clCreateBuffer(context,
      flags | (host != nullptr && bytes > 0 ? CL_MEM_COPY_HOST_PTR : 0),
      std::max(bytes, kMinBufferBytes),
      host != nullptr && bytes > 0 ? const_cast<void*>(host) : nullptr,
      &status);
    check(status, "allocate device memory");
  }
  ~DeviceBuffer()
  {
    if (mem_ != nullptr)
    {
      clReleaseMemObject(mem_);
    }
  }
  DeviceBuffer(DeviceBuffer&& o) noexcept
    : mem_(o.mem_)
  {
    o.mem_ = nullptr;
  }
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept
  {
    std::swap(mem_, o.mem_);
    return *this;
  }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  cl_mem get() const { return mem_; }

private:
  cl_mem mem_ = nullptr;
};

template<typename T>
DeviceBuffer upload(cl_context context, const std::vector<T>& data)
{
  return DeviceBuffer(
    context, CL_MEM_READ_ONLY, data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

template<typename T>
void setArg(cl_kernel kernel, cl_uint index, const T& value)
{
  check(clSetKernelArg(kernel, index, sizeof(T), &value), "set a kernel argument");
}

} // namespace

class OpenClRuntime
{
public:
  cl_device_id device = nullptr;
  cl_context context = nullptr;
  cl_command_queue queue = nullptr;
  cl_program program = nullptr;
  cl_kernel featureCost = nullptr;
  cl_kernel coarseSsd = nullptr;
  std::string deviceName;

  ~OpenClRuntime()
  {
    if (featureCost != nullptr)
    {
      clReleaseKernel(featureCost);
    }
    if (coarseSsd != nullptr)
    {
      clReleaseKernel(coarseSsd);
    }
    if (program != nullptr)
    {
      clReleaseProgram(program);
    }
    if (queue != nullptr)
    {
      clReleaseCommandQueue(queue);
    }
    if (context != nullptr)
    {
      clReleaseContext(context);
    }
  }
};

Backend parseBackend(const std::string& text)
{
  return static_cast<Backend>(choicesOf(kBackendWords).valueOf(text, "The backend"));
}

namespace
{

bool anyPlatformHasAccelerator()
{
  cl_uint platforms = 0;
  if (clGetPlatformIDs(0, nullptr, &platforms) != CL_SUCCESS || platforms == 0)
  {
    return false;
  }
  std::vector<cl_platform_id> ids(platforms);
  clGetPlatformIDs(platforms, ids.data(), nullptr);
  for (cl_platform_id p : ids)
  {
    cl_uint devices = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR, 0, nullptr, &devices) ==
        CL_SUCCESS &&
      devices > 0)
    {
      return true;
    }
  }
  return false;
}

} // namespace

bool openClHasAccelerator()
{
  static const bool answer = anyPlatformHasAccelerator(); // asked once: see the header
  return answer;
}

bool matchesOnOpenCl(Backend backend)
{
  return backend == Backend::OpenCL || (backend == Backend::Auto && openClHasAccelerator());
}

OpenClDevice::OpenClDevice()
  : runtime_(std::make_unique<OpenClRuntime>())
{
}

OpenClDevice::~OpenClDevice() = default;

std::string OpenClDevice::name() const
{
  return runtime_->deviceName;
}

std::shared_ptr<OpenClDevice> OpenClDevice::create(const std::string& extraSource)
{
  std::shared_ptr<OpenClDevice> d(new OpenClDevice());
  OpenClRuntime& r = *d->runtime_;
  cl_uint platforms = 0;
  if (clGetPlatformIDs(0, nullptr, &platforms) != CL_SUCCESS || platforms == 0)
  {
    throw Error("No OpenCL platform is installed.");
  }
  std::vector<cl_platform_id> ids(platforms);
  clGetPlatformIDs(platforms, ids.data(), nullptr);
  // Prefer a GPU on any platform, else the first device of any kind.
  for (cl_device_type wanted : { static_cast<cl_device_type>(CL_DEVICE_TYPE_GPU),
         static_cast<cl_device_type>(CL_DEVICE_TYPE_ALL) })
  {
    for (cl_platform_id p : ids)
    {
      cl_uint n = 0;
      if (clGetDeviceIDs(p, wanted, 1, &r.device, &n) == CL_SUCCESS && n > 0)
      {
        break;
      }
      r.device = nullptr;
    }
    if (r.device != nullptr)
    {
      break;
    }
  }
  if (r.device == nullptr)
  {
    throw Error("No OpenCL device was found.");
  }
  char name[256] = {};
  clGetDeviceInfo(r.device, CL_DEVICE_NAME, sizeof name - 1, name, nullptr);
  r.deviceName = name;
  cl_int status = CL_SUCCESS;
  r.context = clCreateContext(nullptr, 1, &r.device, nullptr, nullptr, &status);
  check(status, "create a context");
  r.queue = clCreateCommandQueue(r.context, r.device, 0, &status);
  check(status, "create a command queue");
  const char* sources[3] = {
    opencl::kFeatureCostSource, opencl::kDenseSsdSource, extraSource.c_str()
  };
  r.program =
    clCreateProgramWithSource(r.context, extraSource.empty() ? 2 : 3, sources, nullptr, &status);
  check(status, "load the kernels");
  if (clBuildProgram(r.program, 1, &r.device, "-cl-std=CL1.2", nullptr, nullptr) != CL_SUCCESS)
  {
    std::size_t size = 0;
    clGetProgramBuildInfo(r.program, r.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
    std::string log(size, '\0');
    clGetProgramBuildInfo(r.program, r.device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
    throw Error("The OpenCL kernels did not build on " + r.deviceName + ": " + log);
  }
  r.featureCost = clCreateKernel(r.program, "featureCost", &status);
  check(status, "create the featureCost kernel");
  r.coarseSsd = clCreateKernel(r.program, "coarseSsd", &status);
  check(status, "create the coarseSsd kernel");
  return d;
}

struct OpenClFeatureScorer::Buffers
{
  DeviceBuffer kind, type, arms, angles, along, across, noise, descriptor, landform, out;
};

OpenClFeatureScorer::OpenClFeatureScorer(std::shared_ptr<OpenClDevice> device,
  const CandidatePool& pool)
  : device_(std::move(device))
  , buffers_(std::make_unique<Buffers>())
  , size_(pool.size())
  , invScale2_(static_cast<float>(1.0 / (pool.heightScale * pool.heightScale)))
{
  cl_context ctx = device_->runtime().context;
  buffers_->kind = upload(ctx, pool.kind);
  buffers_->type = upload(ctx, pool.type);
  buffers_->arms = upload(ctx, pool.arms);
  buffers_->angles = upload(ctx, pool.angles);
  buffers_->along = upload(ctx, pool.along);
  buffers_->across = upload(ctx, pool.across);
  buffers_->noise = upload(ctx, pool.noise);
  buffers_->descriptor = upload(ctx, pool.descriptor);
  buffers_->landform = upload(ctx, pool.landform);
  buffers_->out = DeviceBuffer(ctx, CL_MEM_WRITE_ONLY, size_ * sizeof(float), nullptr);
}

OpenClFeatureScorer::~OpenClFeatureScorer() = default;

std::vector<float> OpenClFeatureScorer::score(const FeatureQuery& q, const MatchWeights& w)
{
  std::vector<float> costs(size_);
  if (size_ == 0)
  {
    return costs;
  }
  OpenClRuntime& r = device_->runtime();
  std::vector<float> packed;
  packed.insert(packed.end(), q.angles.begin(), q.angles.end());
  packed.insert(packed.end(), q.along.begin(), q.along.end());
  packed.insert(packed.end(), q.across.begin(), q.across.end());
  packed.insert(packed.end(), q.noise.begin(), q.noise.end());
  DeviceBuffer qb(r.context, CL_MEM_READ_ONLY, packed.size() * sizeof(float), packed.data());
  DeviceBuffer qd(r.context, CL_MEM_READ_ONLY, sizeof q.descriptor, q.descriptor.data());
  DeviceBuffer qw(r.context, CL_MEM_READ_ONLY, sizeof q.weight, q.weight.data());
  DeviceBuffer ql(r.context, CL_MEM_READ_ONLY, sizeof q.landform, q.landform.data());
  DeviceBuffer qlw(r.context, CL_MEM_READ_ONLY, sizeof q.landformWeight, q.landformWeight.data());
  cl_kernel k = r.featureCost;
  const Buffers& b = *buffers_;
  cl_uint a = 0;
  const DeviceBuffer* inputs[] = { &b.kind,
    &b.type,
    &b.arms,
    &b.angles,
    &b.along,
    &b.across,
    &b.noise,
    &b.descriptor,
    &b.landform,
    &qb,
    &qd,
    &qw,
    &ql,
    &qlw };
  for (const DeviceBuffer* buf : inputs)
  {
    const cl_mem m = buf->get();
    setArg(k, a++, m);
  }
  setArg(k, a++, static_cast<cl_int>(q.type));
  setArg(k, a++, static_cast<cl_int>(q.kind));
  setArg(k, a++, static_cast<cl_int>(q.arms));
  const cl_float4 weights = { { static_cast<float>(w.feature),
    static_cast<float>(w.angle),
    static_cast<float>(w.noise),
    static_cast<float>(w.overlap) } };
  setArg(k, a++, weights);
  setArg(k, a++, static_cast<float>(w.landform));
  setArg(k, a++, static_cast<cl_int>(w.verticalOffset ? 1 : 0));
  setArg(k, a++, invScale2_);
  setArg(k, a++, static_cast<cl_uint>(size_));
  const cl_mem out = b.out.get();
  setArg(k, a++, out);
  const std::size_t local = 64;
  const std::size_t global = (size_ + local - 1) / local * local;
  check(clEnqueueNDRangeKernel(r.queue, k, 1, nullptr, &global, &local, 0, nullptr, nullptr),
    "run featureCost");
  check(clEnqueueReadBuffer(
          r.queue, out, CL_TRUE, 0, size_ * sizeof(float), costs.data(), 0, nullptr, nullptr),
    "read the costs");
  return costs;
}

struct OpenClDenseScorer::Buffers
{
  DeviceBuffer blocks, pairs, quads; // every oriented exemplar's image, concatenated
  DeviceBuffer rowOriented, rowY, imageStart, strides, offsetsX, runStart, outStart;
  DeviceBuffer output;
  std::vector<std::uint8_t> runs;     // groupValid of all, concatenated
  std::vector<std::size_t> runOffset; // where each exemplar's runs start
  std::vector<std::size_t> outOffset; // where each exemplar's costs start
  std::size_t rowCount = 0, maxGroups = 0, outSize = 0;
};

OpenClDenseScorer::OpenClDenseScorer(std::shared_ptr<OpenClDevice> device,
  const DenseMatcher& matcher)
  : device_(std::move(device))
  , matcher_(matcher)
  , buffers_(std::make_unique<Buffers>())
{
  cl_context ctx = device_->runtime().context;
  Buffers& b = *buffers_;
  std::vector<float> blocks, pairs, quads;
  std::vector<int> rowOriented, rowY, imageStart, strides, offsetsX, runStart, outStart;
  for (std::size_t i = 0; i < matcher.oriented().size(); ++i)
  {
    const DenseMatcher::Oriented& o = matcher.oriented()[i];
    imageStart.push_back(static_cast<int>(blocks.size()));
    blocks.insert(blocks.end(), o.coarse.begin(), o.coarse.end());
    pairs.insert(pairs.end(), o.pairs.begin(), o.pairs.end());
    quads.insert(quads.end(), o.quads.begin(), o.quads.end());
    // One spare row: the last work-items read 16 offsets past the final one.
    blocks.resize(blocks.size() + static_cast<std::size_t>(o.coarseStride), 0.0f);
    pairs.resize(pairs.size() + static_cast<std::size_t>(o.coarseStride), 0.0f);
    quads.resize(quads.size() + static_cast<std::size_t>(o.coarseStride), 0.0f);
    strides.push_back(o.coarseStride);
    offsetsX.push_back(o.offsetsX);
    runStart.push_back(static_cast<int>(b.runs.size()));
    b.runOffset.push_back(b.runs.size());
    b.runs.insert(b.runs.end(), o.groupValid.begin(), o.groupValid.end());
    outStart.push_back(static_cast<int>(b.outSize));
    b.outOffset.push_back(b.outSize);
    b.outSize += cellCount(o.offsetsX, o.offsetsY);
    b.maxGroups = std::max(b.maxGroups, static_cast<std::size_t>((o.offsetsX + 15) / 16));
    for (int y = 0; y < o.offsetsY; ++y)
    {
      rowOriented.push_back(static_cast<int>(i));
      rowY.push_back(y);
    }
  }
  if (blocks.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
  {
    throw Error("The exemplars are too large for the OpenCL dense search.");
  }
  b.rowCount = rowY.size();
  b.blocks = upload(ctx, blocks);
  b.pairs = upload(ctx, pairs);
  b.quads = upload(ctx, quads);
  b.rowOriented = upload(ctx, rowOriented);
  b.rowY = upload(ctx, rowY);
  b.imageStart = upload(ctx, imageStart);
  b.strides = upload(ctx, strides);
  b.offsetsX = upload(ctx, offsetsX);
  b.runStart = upload(ctx, runStart);
  b.outStart = upload(ctx, outStart);
  b.output = DeviceBuffer(
    ctx, CL_MEM_WRITE_ONLY, std::max<std::size_t>(1, b.outSize) * sizeof(float), nullptr);
}

OpenClDenseScorer::~OpenClDenseScorer() = default;

std::vector<std::vector<float>> OpenClDenseScorer::coarseCosts(const CoarseQuery& q)
{
  CoarseQuery unpruned = q;
  unpruned.bound = {};
  return matcher_.prunedCoarseCosts(unpruned,
    [this](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
    { return coarseSsd(t, i, r); });
}

std::vector<std::vector<float>> OpenClDenseScorer::coarseSsd(const CoarseTerms& q,
  CoarseImage image,
  const std::vector<std::vector<std::uint8_t>>* runs)
{
  OpenClRuntime& r = device_->runtime();
  const Buffers& b = *buffers_;
  const auto& oriented = matcher_.oriented();
  // The runs to compute: valid ones, of those asked for.
  std::vector<std::uint8_t> asked = b.runs;
  if (runs != nullptr)
  {
    for (std::size_t i = 0; i < oriented.size(); ++i)
    {
      const std::vector<std::uint8_t>& mine = (*runs)[i];
      for (std::size_t g = 0; g < mine.size(); ++g)
      {
        asked[b.runOffset[i] + g] &= mine[g] != 0 ? 1 : 0;
      }
    }
  }
  // As on the CPU, no costs at all for an oriented exemplar nothing is asked of.
  std::vector<std::vector<float>> out(oriented.size());
  for (std::size_t i = 0; i < oriented.size(); ++i)
  {
    if (runs == nullptr ||
      std::any_of((*runs)[i].begin(), (*runs)[i].end(), [](std::uint8_t m) { return m != 0; }))
    {
      out[i].resize(cellCount(oriented[i].offsetsX, oriented[i].offsetsY));
    }
  }
  if (q.empty())
  {
    // Nothing known: every valid offset costs nothing.
    for (std::vector<float>& v : out)
    {
      std::fill(v.begin(), v.end(), 0.0f);
    }
  }
  else if (b.rowCount > 0)
  {
    const DeviceBuffer rows = upload(r.context, q.row);
    const DeviceBuffer columns = upload(r.context, q.column);
    const DeviceBuffer heights = upload(r.context, q.heights);
    const DeviceBuffer weights = upload(r.context, q.weights);
    const DeviceBuffer runMask = upload(r.context, asked);
    cl_kernel k = r.coarseSsd;
    const DeviceBuffer& pixels =
      image == CoarseImage::Blocks ? b.blocks : (image == CoarseImage::Pairs ? b.pairs : b.quads);
    const cl_mem args[] = { pixels.get(),
      b.rowOriented.get(),
      b.rowY.get(),
      b.imageStart.get(),
      b.strides.get(),
      b.offsetsX.get(),
      b.runStart.get(),
      b.outStart.get(),
      rows.get(),
      columns.get(),
      heights.get(),
      weights.get() };
    cl_uint a = 0;
    for (const cl_mem& m : args)
    {
      setArg(k, a++, m);
    }
    setArg(k, a++, static_cast<cl_int>(q.size()));
    const cl_mem mask = runMask.get();
    setArg(k, a++, mask);
    const cl_mem output = b.output.get();
    setArg(k, a++, output);
    const std::size_t global[2] = { b.maxGroups, b.rowCount };
    check(clEnqueueNDRangeKernel(r.queue, k, 2, nullptr, global, nullptr, 0, nullptr, nullptr),
      "run coarseSsd");
    for (std::size_t i = 0; i < oriented.size(); ++i)
    {
      if (!out[i].empty())
      {
        check(clEnqueueReadBuffer(r.queue,
                output,
                CL_FALSE,
                b.outOffset[i] * sizeof(float),
                out[i].size() * sizeof(float),
                out[i].data(),
                0,
                nullptr,
                nullptr),
          "read the coarse costs");
      }
    }
    check(clFinish(r.queue), "finish the dense search");
  }
  // Offsets the kernel skipped hold stale values: +inf, as on the CPU.
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < oriented.size(); ++i)
  {
    if (out[i].empty())
    {
      continue;
    }
    const DenseMatcher::Oriented& o = oriented[i];
    const std::size_t nx = static_cast<std::size_t>(o.offsetsX);
    const std::size_t groups = (nx + 15) / 16;
    for (std::size_t y = 0; y < static_cast<std::size_t>(o.offsetsY); ++y)
    {
      const std::uint8_t* run = asked.data() + b.runOffset[i] + y * groups;
      for (std::size_t g = 0; g < groups; ++g)
      {
        const std::size_t x0 = y * nx + 16 * g;
        const std::size_t x1 = y * nx + std::min(nx, 16 * g + 16);
        float* costs = out[i].data();
        if (run[g] == 0)
        {
          std::fill(costs + x0, costs + x1, inf);
          continue;
        }
        for (std::size_t k = x0; k < x1; ++k)
        {
          costs[k] = o.coarseValid[k] != 0 ? costs[k] : inf;
        }
      }
    }
  }
  return out;
}

} // namespace tsynth
