// The built-in pass types. Declared by passes/ (not core/graph): core never names a concrete pass,
// so only code that links the passes (the fovea executable, tests, the inspector) calls this.
#pragma once

namespace fovea {
// Registers every built-in pass type in graph::passRegistry() (idempotent: a second call finds
// them there and does nothing).
void registerBuiltinPasses();
}  // namespace fovea
