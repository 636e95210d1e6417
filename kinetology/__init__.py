"""kinetology: joint-angle motion in, actiongrams out (an adapter over psgs)."""
