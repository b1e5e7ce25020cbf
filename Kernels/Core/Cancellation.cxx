#include "Core/Cancellation.h"

#include <utility>

namespace tsynth
{

std::atomic<int> openCancellationScopes{ 0 };

namespace
{
// The innermost scope open on this thread (scopes nest: a filter inside a command).
thread_local CancellationScope* currentScope = nullptr;
} // namespace

CancellationScope::CancellationScope(std::function<bool()> shouldStop)
  : shouldStop_(std::move(shouldStop))
  , outer_(currentScope)
{
  currentScope = this;
  openCancellationScopes.fetch_add(1, std::memory_order_relaxed);
}

CancellationScope::~CancellationScope()
{
  currentScope = outer_;
  openCancellationScopes.fetch_sub(1, std::memory_order_relaxed);
}

void pollCancellationInScope()
{
  CancellationScope* scope = currentScope;
  if (scope != nullptr && ++scope->polls_ % kCancellationStride == 0 && scope->shouldStop_ &&
    scope->shouldStop_())
  {
    throw Cancelled();
  }
}

bool cancellationRequested()
{
  CancellationScope* scope = currentScope;
  return scope != nullptr && scope->shouldStop_ && scope->shouldStop_();
}

void checkCancellation()
{
  if (cancellationRequested())
  {
    throw Cancelled();
  }
}

} // namespace tsynth
