// Catches a VTK object's error events so a failure becomes a tsynth::Error
// with our own sentence instead of text printed by VTK.
#pragma once

#include <vtkCallbackCommand.h>
#include <vtkNew.h>

#include <string>

namespace tsynth
{

struct VtkErrorObserver
{
  bool failed = false;
  std::string message;
  vtkNew<vtkCallbackCommand> callback;
  VtkErrorObserver()
  {
    callback->SetClientData(this);
    callback->SetCallback(
      [](vtkObject*, unsigned long, void* self, void* data)
      {
        auto* observer = static_cast<VtkErrorObserver*>(self);
        observer->failed = true;
        if (data != nullptr && observer->message.empty())
        {
          observer->message = static_cast<const char*>(data);
        }
      });
  }
};

} // namespace tsynth
