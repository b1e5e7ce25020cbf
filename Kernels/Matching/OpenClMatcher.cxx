#define CL_TARGET_OPENCL_VERSION 120
#include "OpenClMatcher.h"

#include "../Core/Error.h"
#include "Matching/OpenClSources.h"

#include <CL/cl.h>

#include <algorithm>
#include <cmath>
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

// A cl_mem released when it goes.
class DeviceBuffer
{
public:
  DeviceBuffer() = default;
  DeviceBuffer(cl_context context, cl_mem_flags flags, std::size_t bytes, const void* host)
  {
    cl_int status = CL_SUCCESS;
    mem_ = clCreateBuffer(context,
      flags | (host != nullptr ? CL_MEM_COPY_HOST_PTR : 0),
      std::max<std::size_t>(bytes, 16),
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
  if (text == "auto")
  {
    return Backend::Auto;
  }
  if (text == "opencl")
  {
    return Backend::OpenCL;
  }
  if (text == "cpu")
  {
    return Backend::Cpu;
  }
  throw Error("The backend must be auto, opencl or cpu, not \"" + text + "\".");
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
  DeviceBuffer kind, type, arms, angles, along, across, noise, descriptor, out;
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
    &qb,
    &qd,
    &qw };
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
  std::vector<DeviceBuffer> images;
  std::vector<DeviceBuffer> groups;
  std::vector<DeviceBuffer> outputs;
};

OpenClDenseScorer::OpenClDenseScorer(std::shared_ptr<OpenClDevice> device,
  const DenseMatcher& matcher)
  : device_(std::move(device))
  , matcher_(matcher)
  , buffers_(std::make_unique<Buffers>())
{
  cl_context ctx = device_->runtime().context;
  for (const DenseMatcher::Oriented& o : matcher.oriented())
  {
    // One spare row: the last work-items read 16 offsets past the final one.
    std::vector<float> padded = o.coarse;
    padded.resize(padded.size() + static_cast<std::size_t>(o.coarseStride), 0.0f);
    buffers_->images.push_back(upload(ctx, padded));
    buffers_->groups.push_back(upload(ctx, o.groupValid));
    buffers_->outputs.emplace_back(ctx,
      CL_MEM_WRITE_ONLY,
      static_cast<std::size_t>(o.offsetsX) * static_cast<std::size_t>(o.offsetsY) * sizeof(float),
      nullptr);
  }
}

OpenClDenseScorer::~OpenClDenseScorer() = default;

std::vector<std::vector<float>> OpenClDenseScorer::coarseCosts(const CoarseQuery& q)
{
  OpenClRuntime& r = device_->runtime();
  const auto& oriented = matcher_.oriented();
  std::vector<std::vector<float>> out(oriented.size());
  if (q.row.empty())
  {
    // Nothing known: every valid offset costs nothing.
    for (std::size_t i = 0; i < oriented.size(); ++i)
    {
      out[i].assign(static_cast<std::size_t>(oriented[i].offsetsX) *
          static_cast<std::size_t>(oriented[i].offsetsY),
        0.0f);
    }
  }
  else
  {
    const DeviceBuffer rows = upload(r.context, q.row);
    const DeviceBuffer columns = upload(r.context, q.column);
    const DeviceBuffer heights = upload(r.context, q.listHeights);
    const DeviceBuffer weights = upload(r.context, q.listWeights);
    cl_kernel k = r.coarseSsd;
    for (std::size_t i = 0; i < oriented.size(); ++i)
    {
      const DenseMatcher::Oriented& o = oriented[i];
      out[i].assign(
        static_cast<std::size_t>(o.offsetsX) * static_cast<std::size_t>(o.offsetsY), 0.0f);
      if (out[i].empty())
      {
        continue;
      }
      const cl_mem args[] = { buffers_->images[i].get(),
        rows.get(),
        columns.get(),
        heights.get(),
        weights.get(),
        buffers_->groups[i].get(),
        buffers_->outputs[i].get() };
      setArg(k, 0, args[0]);
      setArg(k, 1, static_cast<cl_int>(o.coarseStride));
      setArg(k, 2, static_cast<cl_int>(o.offsetsX));
      setArg(k, 3, static_cast<cl_int>(o.offsetsY));
      setArg(k, 4, args[1]);
      setArg(k, 5, args[2]);
      setArg(k, 6, args[3]);
      setArg(k, 7, args[4]);
      setArg(k, 8, static_cast<cl_int>(q.row.size()));
      setArg(k, 9, args[5]);
      setArg(k, 10, args[6]);
      const std::size_t global[2] = { static_cast<std::size_t>((o.offsetsX + 15) / 16),
        static_cast<std::size_t>(o.offsetsY) };
      check(clEnqueueNDRangeKernel(r.queue, k, 2, nullptr, global, nullptr, 0, nullptr, nullptr),
        "run coarseSsd");
      check(clEnqueueReadBuffer(r.queue,
              args[6],
              CL_FALSE,
              0,
              out[i].size() * sizeof(float),
              out[i].data(),
              0,
              nullptr,
              nullptr),
        "read the coarse costs");
    }
    check(clFinish(r.queue), "finish the dense search");
  }
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < oriented.size(); ++i)
  {
    for (std::size_t j = 0; j < out[i].size(); ++j)
    {
      if (oriented[i].coarseValid[j] == 0)
      {
        out[i][j] = inf;
      }
    }
  }
  return out;
}

} // namespace tsynth
