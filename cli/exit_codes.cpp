#include "cli/exit_codes.h"

#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "driver/interrupt.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"
#include "output/run_reader.h"

namespace wl::cli {

int exit_code_of(const std::function<int()>& command) {
  try {
    return command();
  } catch (const SceneError& e) {
    std::cerr << "weavelab: bad scene: " << e.what() << "\n";
    return 2;
  } catch (const RunReadError& e) {
    std::cerr << "weavelab: bad target run: " << e.what() << "\n";
    return 2;
  } catch (const FemParameterError& e) {
    std::cerr << "weavelab: bad FEM parameters: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "weavelab: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "weavelab: " << e.what() << "\n";
    return 3;
  }
}

int numerical_failure_is_exit_1(const std::string& name, const std::function<int()>& computation) {
  try {
    return computation();
  } catch (const std::filesystem::filesystem_error&) {
    throw;
  } catch (const SceneError&) {  // a scene the computation cannot take (e.g. a knit without [fem] stiffnesses)
    throw;
  } catch (const std::runtime_error& e) {
    std::cerr << "weavelab: " << name << ": " << e.what() << "\n";
    return 1;
  }
}

int interruptible(const std::string& name, const std::filesystem::path& out, const std::function<int()>& computation) {
  install_interrupt_handlers();
  try {
    return computation();
  } catch (const Interrupted& e) {
    const int signal = interrupt_signal();
    std::cerr << "weavelab: " << name << ": " << interrupted_message(signal) << " in " << e.stage
              << "; the record so far in " << out.string() << "\n";
    return interrupted_exit_code(signal);
  }
}

}  // namespace wl::cli
