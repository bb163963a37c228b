#include "cli_support.hpp"

#include <cstdio>
#include <exception>
#include <iostream>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"

namespace meridian::cli {

int guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << "meridian: error: " << e.what() << "\n";
    return kInputError;
  } catch (const NumericalError& e) {
    std::cerr << "meridian: numerical failure: " << e.what() << "\n";
    return kNumericalError;
  } catch (const IoError& e) {
    std::cerr << "meridian: I/O error: " << e.what() << "\n";
    return kIoError;
  } catch (const Error& e) {
    std::cerr << "meridian: error: " << e.what() << "\n";
    return kInputError;
  } catch (const std::exception& e) {
    std::cerr << "meridian: internal error: " << e.what() << "\n";
    return kInternalError;
  }
}

void emit(const std::string& path, const std::string& text) {
  if (path.empty() || path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  write_file_atomically(path, text);
}

}  // namespace meridian::cli
