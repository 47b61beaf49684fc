// Physics options: copied from <option> (the reader already checked them).
#include "compiler/compiler.h"

namespace simlab::compiler {

void CompileOption(const mjcf::ModelSpec& spec, Model* m) {
  m->opt = spec.option;
  m->model_name = spec.model_name;
  m->release = spec.newer_construct.tag.empty() ? Release::k3_5_1 : Release::k3_12;
}

}  // namespace simlab::compiler
