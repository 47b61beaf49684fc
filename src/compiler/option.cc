// Physics options: copied from <option> (the reader already checked them).
#include "compiler/compiler.h"

namespace simlab::compiler {

void CompileOption(const mjcf::ModelSpec& spec, Model* m) {
  m->opt = spec.option;
  m->model_name = spec.model_name;
}

}  // namespace simlab::compiler
