# nlohmann::json for run.json and `talus params` (Debian: nlohmann-json3-dev).
find_package(nlohmann_json 3.10 CONFIG REQUIRED)
